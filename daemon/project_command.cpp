// `overlayd project`: where world points land in the configured camera, for aligning a grid to a real camera.
#include "daemon/commands.h"
#include "daemon/json_text.h"

#include <cstdio>

namespace overlayd {

namespace {

std::string triple(const glm::dvec3 &p, const char *separator)
{
    return jsonNumber(p.x) + separator + jsonNumber(p.y) + separator + jsonNumber(p.z);
}

} // namespace

std::string projectionsJson(const std::vector<glm::dvec3> &world, const std::vector<ProjectedPoint> &points)
{
    std::string json = "[";
    for (size_t i = 0; i < world.size(); ++i) {
        const ProjectedPoint &p = points[i];
        const bool clipped = p.status == PointStatus::Clipped;
        json += i ? ",\n " : "";
        json += "{\"world\":[" + triple(world[i], ",") + "],\"pixel\":";
        json += clipped ? "null" : "[" + jsonNumber(p.pixel.x) + "," + jsonNumber(p.pixel.y) + "]";
        json += ",\"depth\":" + (clipped ? std::string("null") : jsonNumber(p.depth));
        json += std::string(",\"visible\":") + (p.status == PointStatus::Visible ? "true" : "false") + "}";
    }
    return json + "]\n";
}

std::string projectionsText(const std::vector<glm::dvec3> &world, const std::vector<ProjectedPoint> &points)
{
    std::string text;
    for (size_t i = 0; i < world.size(); ++i) {
        const ProjectedPoint &p = points[i];
        text += "(" + triple(world[i], ", ") + ") -> ";
        if (p.status == PointStatus::Clipped) {
            text += "clipped (behind the camera, beyond the far plane or outside the lens's field)\n";
            continue;
        }
        char line[160];
        std::snprintf(line, sizeof(line), "pixel (%.3f, %.3f), depth %.6f, %s\n", p.pixel.x, p.pixel.y, p.depth,
                      p.status == PointStatus::Visible ? "visible" : "outside the scissor");
        text += line;
    }
    return text;
}

int projectCommand(const std::string &configPath, bool json, const std::vector<double> &coordinates, Logger &logger)
{
    if (coordinates.empty() || coordinates.size() % 3 != 0) {
        logger.error(cat("project: expected X Y Z triples, got ", coordinates.size(), " numbers"));
        return kExitFailure;
    }
    const auto configured = loadCameraLogged(configPath, logger);
    if (!configured)
        return kExitConfigError;
    const Camera *camera = &configured->camera;
    std::vector<glm::dvec3> world;
    for (size_t i = 0; i < coordinates.size(); i += 3)
        world.emplace_back(coordinates[i], coordinates[i + 1], coordinates[i + 2]);
    std::vector<ProjectedPoint> points(world.size());
    camera->projectPoints(world, points);
    // Pixels are memory order inside; the user reads them in the viewport's origin.
    for (ProjectedPoint &point : points)
        point.pixel = camera->viewport().toUser(point.pixel);
    const std::string output = json ? projectionsJson(world, points) : projectionsText(world, points);
    std::fwrite(output.data(), 1, output.size(), stdout);
    return kExitOk;
}

} // namespace overlayd
