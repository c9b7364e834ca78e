// SPDX-License-Identifier: Apache-2.0
// The points file of `overlayd solve-pose` and `overlayd project --points`: one point per line, "x y z u v" (world
// metres, then the pixel in the viewport's origin convention; project reads "x y z" too and ignores u v),
// separated by commas and/or spaces; '#' starts a comment; the first line may be a header row naming the columns
// ("x,y,z,u,v", as a spreadsheet exports). Or JSON, as `overlayd project --json` prints it (points_json.h): a file
// named *.json or starting with '[' or '{'.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "alignment/pose_solver.h"
#include "base/result.h"

namespace overlayd {

inline constexpr size_t kMaxPointsFileBytes = 1 << 20; // either form; kMaxCorrespondences bounds the points
inline constexpr size_t kQuotedFieldBytes = 32;        // how much of a refused field a message quotes

// One line of the text form: the world point, and its pixel when the line has five numbers.
struct PointRow {
    glm::dvec3 world;
    std::optional<glm::dvec2> pixel;
};

// Pixels come back as written (the user's origin); the caller converts them. Errors name file:line.
Result<std::vector<Correspondence>> readPointsFile(const std::string &path);
Result<std::vector<Correspondence>> parsePoints(const std::string &text, const std::string &name);
// The text form's rows: five numbers each, or with needPixels false three or five.
Result<std::vector<PointRow>> parsePointRows(const std::string &text, const std::string &name, bool needPixels);
// project's points: the world points of either form, their pixels (if any) ignored.
Result<std::vector<glm::dvec3>> parseWorldPoints(const std::string &text, const std::string &name);

} // namespace overlayd
