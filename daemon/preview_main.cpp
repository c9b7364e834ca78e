// overlayd-preview: renders the built-in synthetic scene through the projection library into a PNG.
//
// A stand-in for `overlayd render` until the daemon lands: a checkerboard ground plane is ray-traced per pixel
// through the camera (unproject + ray-plane intersection), then a ground grid of the same spacing and an XYZ
// axes triad are projected as 3D segments (clipped, curved through the lens) and drawn on top. If projection is
// right, every grid line lies on a checker edge.
#include <cmath>
#include <cstdio>
#include <string>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "projection/camera.h"

namespace {

using namespace overlayd;

constexpr int kWidth = 960, kHeight = 540;
constexpr double kSquare = 0.5; // metres per checker square and grid cell
constexpr int kGridCells = 12;  // grid half-extent in cells

Result<Camera> demoCamera()
{
    // A vehicle-style camera 1.6 m up, behind and left of the origin, with a mildly barrel-distorting lens.
    auto pose = poseLookAt({-3.0, -4.0, 1.6}, {1.0, 0.5, 0.0}, {0.0, 0.0, 1.0});
    const PinholeIntrinsics k{560.0, 560.0, (kWidth - 1) / 2.0, (kHeight - 1) / 2.0, 0.0, kWidth, kHeight};
    auto projection = Projection::pinhole(k, 0.05, 200.0, DepthRange::ZeroToOne);
    auto viewport = Viewport::create({kWidth, kHeight});
    if (!pose)
        return pose.error();
    if (!projection)
        return projection.error();
    if (!viewport)
        return viewport.error();
    Distortion lens{DistortionModel::RadialTangential, {-0.28, 0.08, 0.0005, -0.0003, -0.01}};
    return Camera::create(*pose, *projection, lens, *viewport);
}

// Colour (BGR) of the scene along one ray: checker squares on the ground plane, sky elsewhere.
cv::Vec3d sceneColour(const Result<Ray> &ray)
{
    const Plane ground = Plane::fromPointNormal({0, 0, 0}, {0, 0, 1});
    if (ray) {
        if (auto t = intersect(*ray, ground)) {
            const glm::dvec3 hit = ray->at(*t);
            const long parity = std::lround(std::floor(hit.x / kSquare) + std::floor(hit.y / kSquare));
            return (parity & 1) ? cv::Vec3d(60, 60, 60) : cv::Vec3d(150, 150, 150);
        }
    }
    return {200, 170, 140};
}

// Ray-traces the ground with 3x3 samples per pixel, so that the far checkers blend instead of aliasing.
void renderGround(const Camera &camera, cv::Mat &image)
{
    constexpr int kSub = 3;
    for (int v = 0; v < image.rows; ++v) {
        for (int u = 0; u < image.cols; ++u) {
            cv::Vec3d sum(0, 0, 0);
            for (int j = 0; j < kSub; ++j)
                for (int i = 0; i < kSub; ++i)
                    sum += sceneColour(camera.unproject({u + (i + 0.5) / kSub - 0.5, v + (j + 0.5) / kSub - 0.5}));
            image.at<cv::Vec3b>(v, u) = sum / double(kSub * kSub);
        }
    }
}

void drawPolylines(const Polylines &lines, const cv::Scalar &colour, int thickness, cv::Mat &image)
{
    constexpr int kShift = 4; // sub-pixel precision for cv::line
    for (std::size_t i = 0; i < lines.size(); ++i) {
        const auto points = lines[i];
        for (std::size_t j = 1; j < points.size(); ++j) {
            const cv::Point a(std::lround(points[j - 1].x * 16), std::lround(points[j - 1].y * 16));
            const cv::Point b(std::lround(points[j].x * 16), std::lround(points[j].y * 16));
            cv::line(image, a, b, colour, thickness, cv::LINE_AA, kShift);
        }
    }
}

void drawGrid(const Camera &camera, cv::Mat &image)
{
    Polylines lines;
    const double extent = kGridCells * kSquare;
    for (int i = -kGridCells; i <= kGridCells; ++i) {
        const double c = i * kSquare;
        camera.projectSegment({c, -extent, 0, 1}, {c, extent, 0, 1}, lines);
        camera.projectSegment({-extent, c, 0, 1}, {extent, c, 0, 1}, lines);
    }
    drawPolylines(lines, cv::Scalar(0, 255, 255), 1, image);
}

void drawAxes(const Camera &camera, cv::Mat &image)
{
    const glm::dvec4 origin(0, 0, 0, 1);
    const struct {
        glm::dvec4 tip;
        cv::Scalar colour;
        const char *name;
    } axes[] = {{{1, 0, 0, 1}, {0, 0, 255}, "X"}, {{0, 1, 0, 1}, {0, 255, 0}, "Y"}, {{0, 0, 1, 1}, {255, 0, 0}, "Z"}};
    for (const auto &axis : axes) {
        Polylines line;
        camera.projectSegment(origin, axis.tip, line);
        drawPolylines(line, axis.colour, 3, image);
        const ProjectedPoint tip = camera.project(axis.tip);
        if (tip.status != PointStatus::Clipped)
            std::printf("axis %s tip (%g, %g, %g) -> pixel (%.3f, %.3f), depth %.6f\n", axis.name, axis.tip.x,
                        axis.tip.y, axis.tip.z, tip.pixel.x, tip.pixel.y, tip.depth);
    }
}

} // namespace

int main(int argc, char **argv)
{
    const std::string output = argc > 1 ? argv[1] : "out/preview.png";
    auto camera = demoCamera();
    if (!camera) {
        std::fprintf(stderr, "overlayd-preview: %s\n", camera.error().message.c_str());
        return 1;
    }
    cv::Mat image(kHeight, kWidth, CV_8UC3);
    renderGround(*camera, image);
    drawGrid(*camera, image);
    drawAxes(*camera, image);
    if (!cv::imwrite(output, image)) {
        std::fprintf(stderr, "overlayd-preview: cannot write %s\n", output.c_str());
        return 1;
    }
    std::printf("wrote %s (%dx%d): checkerboard ground ray-traced through the camera, grid and axes projected\n",
                output.c_str(), kWidth, kHeight);
    return 0;
}
