// SPDX-License-Identifier: Apache-2.0
// Negotiation: what a capture device offers, and the choice of format, size and rate against a request.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "media/pixel_format.h"

namespace overlayd {

// One VIDIOC_ENUM_FRAMESIZES answer: a discrete size has min == max.
struct SizeRange {
    unsigned minWidth = 0, maxWidth = 0, stepWidth = 1;
    unsigned minHeight = 0, maxHeight = 0, stepHeight = 1;
};

// One VIDIOC_ENUM_FRAMEINTERVALS answer, as frame rates: a discrete rate has min == max.
struct RateRange {
    double minFps = 0.0, maxFps = 0.0;
};

struct OfferedFormat {
    uint32_t fourcc = 0;
    std::vector<SizeRange> sizes; // empty: the driver does not enumerate sizes (S_FMT decides)
};

struct Request {
    const PixelFormatInfo *format = nullptr;
    unsigned width = 0, height = 0;
    double fps = 0.0;
};

enum class Verdict { Valid, Adjusted, Invalid };

struct FormatChoice {
    Verdict verdict = Verdict::Invalid;
    uint32_t fourcc = 0; // the device fourcc to set: the format, its multi-plane variant, or MJPEG
    unsigned width = 0, height = 0;
    std::string message; // Invalid: what the device offers
};

// Prefers the requested format, then its multi-memory-plane variant (NV12M for NV12), then MJPEG (decoded);
// the size is the offered one nearest in area when the requested one is not offered.
FormatChoice chooseFormat(const Request &request, std::span<const OfferedFormat> offers);

// The offered rate nearest to the wanted one; the wanted one when the driver does not enumerate rates.
double chooseRate(double wantedFps, std::span<const RateRange> rates);

// "YUYV 320x180..1920x1080, NV12 640x480 1280x720, MJPG": for the Invalid message.
std::string describeOffers(std::span<const OfferedFormat> offers);

// "1920x1080@30 YUYV": one side of the adjustment log line.
std::string describeMode(unsigned width, unsigned height, double fps, const std::string &format);

} // namespace overlayd
