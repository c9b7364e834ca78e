// The points file of `overlayd solve-pose`: one correspondence per line, "x y z u v" (world metres, then the pixel
// in the viewport's origin convention), separated by commas and/or spaces; '#' starts a comment. Or JSON, as
// `overlayd project --json` prints it (points_json.h): a file named *.json or starting with '[' or '{'.
#pragma once

#include <string>
#include <vector>

#include "alignment/pose_solver.h"
#include "base/result.h"

namespace overlayd::alignment {

inline constexpr size_t kMaxPointsFileBytes = 1 << 20; // either form; kMaxCorrespondences bounds the points

// Pixels come back as written (the user's origin); the caller converts them. Errors name file:line.
Result<std::vector<Correspondence>> readPointsFile(const std::string &path);
Result<std::vector<Correspondence>> parsePoints(const std::string &text, const std::string &name);

} // namespace overlayd::alignment
