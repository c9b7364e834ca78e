// `overlayd project`: where world points land in the configured camera, for aligning a grid to a real camera.
#include "daemon/commands.h"

#include <charconv>
#include <cmath>
#include <cstdio>

namespace overlayd {

namespace {

std::string number(double value)
{
    if (!std::isfinite(value))
        return "null";
    char text[32];
    const auto result = std::to_chars(text, text + sizeof(text), value);
    return std::string(text, result.ptr);
}

std::string triple(const glm::dvec3 &p, const char *separator)
{
    return number(p.x) + separator + number(p.y) + separator + number(p.z);
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
        json += clipped ? "null" : "[" + number(p.pixel.x) + "," + number(p.pixel.y) + "]";
        json += ",\"depth\":" + (clipped ? std::string("null") : number(p.depth));
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
    auto config = loadConfigLogged(configPath, logger);
    if (!config)
        return kExitConfigError;
    // The configured frame size: a device that negotiates another size scales its intrinsics the same way.
    auto camera = config->camera.build(config->source.width, config->source.height);
    if (!camera) {
        logger.error(cat(configPath, ": camera: ", camera.error().message));
        return kExitConfigError;
    }
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
