// `overlayd unproject`: the world ray behind each pixel and where it meets a plane (the ground z = 0 by default),
// the inverse of `project` through the same Camera (distortion undone exactly).
#include <cstdio>

#include "base/json_text.h"
#include "tools/commands.h"

namespace overlayd {

int unprojectCommand(const std::string &configPath, bool json, const std::vector<double> &planeValues,
                     const std::vector<double> &coordinates, Logger &logger)
{
    if (coordinates.empty() || coordinates.size() % 2 != 0) {
        logger.error(cat("unproject: expected U V pairs, got ", coordinates.size(), " numbers"));
        return kExitFailure;
    }
    Plane plane;
    if (!planeValues.empty()) {
        const glm::dvec3 normal(planeValues[0], planeValues[1], planeValues[2]);
        const double length = glm::length(normal);
        if (planeValues.size() != 4 || !(length > 1e-12)) {
            logger.error("unproject: --plane wants \"nx ny nz d\" (the plane n.x + d = 0) with a non-zero normal");
            return kExitFailure;
        }
        plane = Plane{normal / length, planeValues[3] / length};
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
