// SPDX-License-Identifier: Apache-2.0
// The project's pixel formats as libcamera's (DRM fourccs) and back: exact, by memory layout, never by name.
#pragma once

#include <optional>
#include <string>

#include <libcamera/pixel_format.h>

#include "media/pixel_format.h"

namespace overlayd {

// nullopt / nullptr when the other side has no format with the same bytes in memory.
std::optional<libcamera::PixelFormat> toLibcamera(const PixelFormatInfo &format);
const PixelFormatInfo *fromLibcamera(const libcamera::PixelFormat &format);
// "NV12", or libcamera's own name ("SRGGB10_CSI2P") for a format the project has no name for.
std::string formatName(const libcamera::PixelFormat &format);

} // namespace overlayd
