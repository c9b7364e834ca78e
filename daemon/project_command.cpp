// `overlayd project`: where world points land in the configured camera, for aligning a grid to a real camera.
#include "daemon/commands.h"

#include "alignment/points_file.h"
#include "base/number_text.h"
#include "daemon/json_text.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>

#include <glm/geometric.hpp>

namespace overlayd {

namespace {

std::string triple(const glm::dvec3 &p, const char *separator)
{
    return jsonNumber(p.x) + separator + jsonNumber(p.y) + separator + jsonNumber(p.z);
}

} // namespace

PointReport explainPoint(const Camera &camera, const glm::dvec3 &world, const ProjectedPoint &point)
{
    const glm::dvec4 eye = camera.view() * glm::dvec4(world, 1.0);
    PointReport report{-eye.z, nullptr};
    if (point.status == PointStatus::Outside)
        report.reason = camera.viewport().inWindow(point.pixel) ? "outside-scissor" : "outside-viewport";
    if (point.status != PointStatus::Clipped)
        return report;
    const Projection &projection = camera.projection();
    const glm::dvec4 clip = projection.matrix() * eye;
    const double nearNdc = projection.depthRange() == DepthRange::ZeroToOne ? 0.0 : -1.0;
    if (camera.seesBehind() && glm::length(glm::dvec3(eye)) < camera.nearDistance())
        report.reason = "before-near"; // such a lens clips by the near sphere, and sees behind the camera
    else if (camera.seesBehind())
        report.reason = clip.z > clip.w && clip.w > 0.0 ? "beyond-far" : "outside-image-circle";
    else if (projection.isPerspective() && clip.w <= 0.0)
        report.reason = "behind-camera";
    else if (clip.z < nearNdc * clip.w)
        report.reason = "before-near";
    else if (clip.z > clip.w)
        report.reason = "beyond-far";
    else
        report.reason = "outside-image-circle";
    return report;
}

namespace {

struct Projected {
    std::vector<ProjectedPoint> points; // pixels in the viewport's origin
    std::vector<PointReport> reports;
};

Projected projectAll(const Camera &camera, const std::vector<glm::dvec3> &world)
{
    Projected out;
    out.points.resize(world.size());
    camera.projectPoints(world, out.points);
    for (size_t i = 0; i < world.size(); ++i)
        out.reports.push_back(explainPoint(camera, world[i], out.points[i]));
    // Pixels are memory order inside; the user reads them in the viewport's origin.
    for (ProjectedPoint &point : out.points)
        point.pixel = camera.viewport().toUser(point.pixel);
    return out;
}

} // namespace

std::string projectionsJson(const std::vector<glm::dvec3> &world, const std::vector<ProjectedPoint> &points,
                            const std::vector<PointReport> &reports)
{
    std::string json = "[";
    for (size_t i = 0; i < world.size(); ++i) {
        const ProjectedPoint &p = points[i];
        const bool clipped = p.status == PointStatus::Clipped;
        json += i ? ",\n " : "";
        json += "{\"world\":[" + triple(world[i], ",") + "],\"pixel\":";
        json += clipped ? "null" : "[" + jsonNumber(p.pixel.x) + "," + jsonNumber(p.pixel.y) + "]";
        json += ",\"depth\":" + (clipped ? std::string("null") : jsonNumber(p.depth));
        json += ",\"distance\":" + jsonNumber(reports[i].distance);
        json += std::string(",\"visible\":") + (p.status == PointStatus::Visible ? "true" : "false");
        json += ",\"reason\":" + (reports[i].reason ? jsonString(reports[i].reason) : std::string("null")) + "}";
    }
    return json + "]\n";
}

std::string projectionsText(const std::vector<glm::dvec3> &world, const std::vector<ProjectedPoint> &points,
                            const std::vector<PointReport> &reports)
{
    std::string text;
    for (size_t i = 0; i < world.size(); ++i) {
        const ProjectedPoint &p = points[i];
        const PointReport &r = reports[i];
        text += "(" + triple(world[i], ", ") + ") -> ";
        if (p.status == PointStatus::Clipped)
            text += formatted("no pixel: %s (%.3f m %s the camera)\n", r.reason, std::abs(r.distance),
                              r.distance < 0.0 ? "behind" : "in front of");
        else
            text += formatted("pixel (%.3f, %.3f), depth %.6f, %.3f m in front, %s\n", p.pixel.x, p.pixel.y, p.depth,
                              r.distance, r.reason ? r.reason : "visible");
    }
    return text;
}

std::string projectJson(const Camera &camera, const std::vector<glm::dvec3> &world)
{
    const Projected projected = projectAll(camera, world);
    return projectionsJson(world, projected.points, projected.reports);
}

std::string projectText(const Camera &camera, const std::vector<glm::dvec3> &world)
{
    const Projected projected = projectAll(camera, world);
    return projectionsText(world, projected.points, projected.reports);
}

namespace {

// The points of --points: a file, or stdin for "-", in solve-pose's points format (its marks file works here).
Result<std::vector<glm::dvec3>> readPoints(const std::string &path)
{
    std::FILE *file = path == "-" ? stdin : std::fopen(path.c_str(), "rb");
    if (!file)
        return makeError(ErrorCode::NotFound, "cannot open " + path + ": " + std::strerror(errno));
    std::string text(alignment::kMaxPointsFileBytes + 1, '\0');
    text.resize(std::fread(text.data(), 1, text.size(), file));
    if (file != stdin)
        std::fclose(file);
    if (text.size() > alignment::kMaxPointsFileBytes)
        return makeError(ErrorCode::Malformed,
                         path + ": more than " + std::to_string(alignment::kMaxPointsFileBytes) + " bytes");
    return alignment::parseWorldPoints(text, path == "-" ? "stdin" : path);
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
