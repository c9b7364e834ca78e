// SPDX-License-Identifier: Apache-2.0
// The JSON form of solve-pose's points file: what `overlayd project --json` prints, so its output can go back in.
//
//   [{"world": [x, y, z], "pixel": [u, v]}, ...]
//
// Other keys of an element (project's "depth", "reason", ...) are ignored; a null pixel is refused (that point had
// none). Errors name the file, the line of the element and its index.
#pragma once

#include <string>
#include <vector>

#include "alignment/pose_solver.h"
#include "base/result.h"

namespace overlayd {

// Deeper nesting than a points file needs is refused before the parser sees it.
inline constexpr int kMaxPointsJsonDepth = 3;

// Whether text is a JSON points file: named *.json, or its first non-blank character is '[' or '{'.
bool looksLikeJson(const std::string &text, const std::string &name);
Result<std::vector<Correspondence>> parsePointsJson(const std::string &text, const std::string &name);

} // namespace overlayd
