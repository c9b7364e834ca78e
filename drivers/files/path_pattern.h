// SPDX-License-Identifier: Apache-2.0
// Numbered file names and file types by extension ("frames/%04d.png") without handing a user's string to printf.
#pragma once

#include <cstdint>
#include <string>

#include "base/result.h"

namespace overlayd {

// True when the path holds one %d conversion (optionally zero-padded, "%04d"); "%%" is a literal percent.
bool hasIndexPattern(const std::string &pattern);
// The path with its %d conversion replaced by `index`; a path without one comes back unchanged. Any other
// conversion is an InvalidArgument error.
Result<std::string> formatIndex(const std::string &pattern, uint64_t index);

// ".png" for "out/Snap.PNG": what sources and sinks pick their file type by.
std::string lowerExtension(const std::string &path);

} // namespace overlayd
