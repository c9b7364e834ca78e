// SPDX-License-Identifier: Apache-2.0
// The projection queries of alignment/point_queries.h: `project`'s and `unproject`'s output, and /api/project's.
#include "alignment/point_queries.h"

#include <cmath>
#include <optional>

#include <glm/geometric.hpp>

#include "base/json_text.h"
#include "base/number_text.h"

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

std::string vec(const glm::dvec3 &v)
{
    return "[" + jsonNumber(v.x) + "," + jsonNumber(v.y) + "," + jsonNumber(v.z) + "]";
}

std::string fixed(double value)
{
    return formatted("%.6f", value);
}

std::string readable(const glm::dvec3 &v)
{
    return "(" + fixed(v.x) + ", " + fixed(v.y) + ", " + fixed(v.z) + ")";
}

struct Unprojected {
    glm::dvec2 pixel; // as the user gave it
    std::optional<Ray> ray;
    std::optional<glm::dvec3> hit;
    std::string reason; // why no ray or no hit
};

Unprojected unprojectOne(const Camera &camera, const Plane &plane, const glm::dvec2 &userPixel)
{
    Unprojected out{userPixel, {}, {}, {}};
    const glm::dvec2 pixel = camera.viewport().toTopLeft(userPixel);
    auto ray = camera.unproject(pixel);
    if (!ray) {
        out.reason = ray.error().message;
        return out;
    }
    out.ray = *ray;
    if (const auto t = intersect(*ray, plane))
        out.hit = ray->at(*t);
    else
        out.reason = std::abs(glm::dot(plane.normal, ray->direction)) < 1e-12
                         ? "the ray runs parallel to the plane"
                         : "the plane is behind the camera along this ray (the pixel looks above the horizon)";
    return out;
}

} // namespace

std::string unprojectJson(const Camera &camera, const Plane &plane, const std::vector<glm::dvec2> &pixels)
{
    std::string output = "[";
    for (size_t i = 0; i < pixels.size(); ++i) {
        const Unprojected u = unprojectOne(camera, plane, pixels[i]);
        output +=
            std::string(i ? ",\n " : "") + "{\"pixel\":[" + jsonNumber(u.pixel.x) + "," + jsonNumber(u.pixel.y) + "]";
        output += ",\"origin\":" + (u.ray ? vec(u.ray->origin) : "null");
        output += ",\"direction\":" + (u.ray ? vec(u.ray->direction) : "null");
        output += ",\"hit\":" + (u.hit ? vec(*u.hit) : "null");
        output += ",\"reason\":" + (u.reason.empty() ? "null" : jsonString(u.reason)) + "}";
    }
    return output + "]\n";
}

std::string unprojectText(const Camera &camera, const Plane &plane, const std::vector<glm::dvec2> &pixels)
{
    std::string output;
    for (const glm::dvec2 &pixel : pixels) {
        const Unprojected u = unprojectOne(camera, plane, pixel);
        output += "(" + fixed(u.pixel.x) + ", " + fixed(u.pixel.y) + ") -> ";
        if (!u.ray) {
            output += "no ray: " + u.reason + "\n";
            continue;
        }
        output += "ray from " + readable(u.ray->origin) + " along " + readable(u.ray->direction) + "; ";
        output += u.hit ? "meets the plane at " + readable(*u.hit) + ", " + fixed(glm::length(*u.hit - u.ray->origin)) +
                              " m away\n"
                        : "misses the plane: " + u.reason + "\n";
    }
    return output;
}

} // namespace overlayd
