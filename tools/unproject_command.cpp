// SPDX-License-Identifier: Apache-2.0
// `overlayd unproject`: the world ray behind each pixel and where it meets a plane (the ground z = 0 by default),
// the inverse of `project` through the same Camera (distortion undone exactly).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>

#include "base/number_text.h"
#include "tools/commands.h"

namespace overlayd {

namespace {

// --plane "nx ny nz d" as a unit normal, or why not. The normal is scaled by its largest component before it is
// normalised: its length then neither overflows nor underflows, so a plane written large or small is the same plane.
Result<Plane> planeOf(const std::vector<double> &values)
{
    if (values.size() != 4)
        return makeError(ErrorCode::InvalidArgument, "--plane wants \"nx ny nz d\" (the plane n.x + d = 0)");
    if (const std::string why = numbersRefusal(values, {"nx", "ny", "nz", "d"}, "--plane", kAnyMagnitude); !why.empty())
        return makeError(ErrorCode::InvalidArgument, why);
    const glm::dvec3 normal(values[0], values[1], values[2]);
    const double largest = std::max({std::abs(normal.x), std::abs(normal.y), std::abs(normal.z)});
    if (!(largest > 0.0))
        return makeError(ErrorCode::InvalidArgument, "--plane: the normal (nx ny nz) must not be zero");
    const glm::dvec3 scaled = normal / largest;
    const double length = glm::length(scaled);
    const double offset = values[3] / largest / length;
    if (!std::isfinite(offset))
        return makeError(ErrorCode::InvalidArgument, "--plane: d is too far for a normal this small");
    return Plane{scaled / length, offset};
}

} // namespace

int unprojectCommand(const std::string &configPath, bool json, const std::vector<double> &planeValues,
                     const std::vector<double> &coordinates, Logger &logger)
{
    if (coordinates.empty() || coordinates.size() % 2 != 0) {
        logger.error(cat("unproject: expected U V pairs, got ", coordinates.size(), " numbers"));
        return kExitFailure;
    }
    if (const std::string why = numbersRefusal(coordinates, {"U", "V"}, "pixel", kAnyMagnitude); !why.empty()) {
        logger.error("unproject: " + why);
        return kExitConfigError;
    }
    Plane plane;
    if (!planeValues.empty()) {
        auto given = planeOf(planeValues);
        if (!given) {
            logger.error("unproject: " + given.error().message);
            return kExitConfigError;
        }
        plane = *given;
    }
    const auto configured = loadCameraLogged(configPath, logger);
    if (!configured)
        return kExitConfigError;
    std::vector<glm::dvec2> pixels;
    for (size_t i = 0; i < coordinates.size(); i += 2)
        pixels.emplace_back(coordinates[i], coordinates[i + 1]);
    const std::string output =
        json ? unprojectJson(configured->camera, plane, pixels) : unprojectText(configured->camera, plane, pixels);
    std::fwrite(output.data(), 1, output.size(), stdout);
    return kExitOk;
}

} // namespace overlayd
