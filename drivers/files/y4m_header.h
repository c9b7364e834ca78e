// SPDX-License-Identifier: Apache-2.0
// The YUV4MPEG2 stream header: parsing what files hold, and writing what our sink produces.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "base/result.h"
#include "media/colorimetry.h"

namespace overlayd {

// 8-bit colour spaces only. C420jpeg, C420mpeg2, C420paldv and C420 differ only in chroma siting, which the
// converters do not model: all are 4:2:0.
enum class Y4mChroma { C420, C422, C444, Mono };

struct Y4mHeader {
    unsigned width = 0, height = 0;
    unsigned fpsNum = 30, fpsDen = 1;
    Y4mChroma chroma = Y4mChroma::C420;
    std::string chromaTag = "420jpeg"; // as written in the file
    std::optional<ColourRange> range;  // from ffmpeg's XCOLORRANGE extension, when present

    unsigned hSub() const { return chroma == Y4mChroma::C420 || chroma == Y4mChroma::C422 ? 2 : 1; }
    unsigned vSub() const { return chroma == Y4mChroma::C420 ? 2 : 1; }
    // Bytes of one frame's samples (after its FRAME line).
    size_t frameBytes() const;
};

// One header line without its newline. Errors are Malformed (or Unsupported for a valid but unsupported colour
// space) and start with `path`.
Result<Y4mHeader> parseY4mHeader(std::string_view line, const std::string &path);
// The line our sink writes, with its newline.
std::string formatY4mHeader(const Y4mHeader &header);

// An exact ratio for the common rates (30000:1001 for 29.97) and otherwise microsecond precision; 0 -> 30:1.
void fpsToRatio(double fps, unsigned &num, unsigned &den);

} // namespace overlayd
