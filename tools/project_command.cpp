// SPDX-License-Identifier: Apache-2.0
// `overlayd project`: where world points land in the configured camera, for aligning a grid to a real camera.
#include "alignment/points_file.h"
#include "base/number_text.h"
#include "tools/commands.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>

#include <glm/geometric.hpp>

namespace overlayd {

namespace {

// The points of --points: a file, or stdin for "-", in solve-pose's points format (its marks file works here).
Result<std::vector<glm::dvec3>> readPoints(const std::string &path)
{
    std::FILE *file = path == "-" ? stdin : std::fopen(path.c_str(), "rb");
    if (!file)
        return makeError(ErrorCode::NotFound, "cannot open " + path + ": " + std::strerror(errno));
    std::string text(kMaxPointsFileBytes + 1, '\0');
    text.resize(std::fread(text.data(), 1, text.size(), file));
    if (file != stdin)
        std::fclose(file);
    if (text.size() > kMaxPointsFileBytes)
        return makeError(ErrorCode::Malformed, path + ": more than " + std::to_string(kMaxPointsFileBytes) + " bytes");
    return parseWorldPoints(text, path == "-" ? "stdin" : path);
}

} // namespace

int projectCommand(const std::string &configPath, bool json, const std::vector<double> &coordinates,
                   const std::string &pointsPath, const std::string &size, Logger &logger)
{
    std::vector<glm::dvec3> world;
    if (!pointsPath.empty()) {
        if (!coordinates.empty()) {
            logger.error("project: give the points either as coordinates or with --points, not both");
            return kExitFailure;
        }
        auto points = readPoints(pointsPath);
        if (!points) {
            logger.error("project: " + points.error().message);
            return kExitFailure;
        }
        world = std::move(*points);
        if (world.empty()) {
            logger.error("project: " + pointsPath + " holds no points");
            return kExitFailure;
        }
    } else {
        if (coordinates.empty() || coordinates.size() % 3 != 0) {
            logger.error(
                cat("project: expected X Y Z triples (or --points FILE), got ", coordinates.size(), " numbers"));
            return kExitFailure;
        }
        if (const std::string why = numbersRefusal(coordinates, {"X", "Y", "Z"}, "point", kAnyMagnitude);
            !why.empty()) {
            logger.error("project: " + why);
            return kExitConfigError;
        }
        for (size_t i = 0; i < coordinates.size(); i += 3)
            world.emplace_back(coordinates[i], coordinates[i + 1], coordinates[i + 2]);
    }
    const auto configured = loadCameraLogged(configPath, logger, size);
    if (!configured)
        return kExitConfigError;
    const std::string output = json ? projectJson(configured->camera, world) : projectText(configured->camera, world);
    std::fwrite(output.data(), 1, output.size(), stdout);
    return kExitOk;
}

} // namespace overlayd
