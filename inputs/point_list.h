// SPDX-License-Identifier: Apache-2.0
// A path file: world points another program writes (a planned route, a trajectory), one "x y z" per line in
// metres, separated by spaces and/or commas; '#' starts a comment, blank lines are skipped.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "base/result.h"

namespace overlayd {

inline constexpr size_t kMaxPathPoints = 10000;
inline constexpr size_t kMaxPathFileBytes = 1 << 20;

// The points, or a Malformed error naming "name:line" and what is wrong (a missing or extra number, a value that is
// not a finite number or outside kAnyMagnitude, more than kMaxPathPoints points). An empty text is an empty path.
Result<std::vector<glm::dvec3>> parsePointList(std::string_view text, const std::string &name);

} // namespace overlayd
