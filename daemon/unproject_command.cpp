// `overlayd unproject`: the world ray behind each pixel and where it meets a plane (the ground z = 0 by default),
// the inverse of `project` through the same Camera (distortion undone exactly).
#include <cstdio>

#include "daemon/commands.h"
#include "daemon/json_text.h"

namespace overlayd {

namespace {

std::string vec(const glm::dvec3 &v)
{
    return "[" + jsonNumber(v.x) + "," + jsonNumber(v.y) + "," + jsonNumber(v.z) + "]";
}

std::string fixed(double value)
{
    char text[32];
    std::snprintf(text, sizeof(text), "%.6f", value);
    return text;
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
