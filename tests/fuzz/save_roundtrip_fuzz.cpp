// SPDX-License-Identifier: Apache-2.0
// libFuzzer target: the live camera survives a save. The input is a PUT /api/camera body (JSON); when the change is
// accepted over the config's camera, the changed camera is saved into the drop-in beside the config (merged with
// what a fixed earlier drop-in holds), the config is loaded again through the loader, and the loaded camera must
// project a fixed set of world points exactly as the live one does. Anything else aborts: a save that fails, a
// saved config that does not load, a pixel that moved.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <unistd.h>
#include <vector>

#include "config/camera_request.h"
#include "config/daemon_config.h"
#include "config/live_drop_in.h"

namespace {

constexpr unsigned kWidth = 160, kHeight = 120;

constexpr std::string_view kConfig = R"(
[source]
kind = "synthetic"
format = "YUYV"
width = 160
height = 120
fps = 30.0
[camera]
position = [0.0, -6.0, 3.0]
yaw = 90.0
pitch = 25.0
fov = 60.0
[[sink]]
kind = "null"
)";

// What an earlier save may have left: a key the save does not write (kept) and camera keys it replaces.
constexpr std::string_view kEarlierDropIn =
    "# an earlier save\n[camera]\nframe = \"world\"\n"
    "near = 0.5\npinhole = { fx = 100.0, fy = 100.0, cx = 80.0, cy = 60.0 }\ndistortion = { model = \"plumb_bob\", "
    "coefficients = [0.1, 0.0, 0.0, 0.0, 0.0] }\n";

std::vector<glm::dvec3> worldPoints()
{
    std::vector<glm::dvec3> points;
    for (double x : {-30.0, -4.0, -0.5, 0.0, 1.5, 6.0})
        for (double y : {-20.0, -6.0, -1.0, 0.5, 3.0, 40.0, 900.0})
            for (double z : {-2.0, 0.0, 1.0, 3.0, 10.0})
                points.emplace_back(x, y, z);
    return points;
}

struct Fixture {
    std::filesystem::path folder =
        std::filesystem::temp_directory_path() / ("save_roundtrip_fuzz-" + std::to_string(getpid()));
    std::string configPath;
    overlayd::CameraSpec live;
    std::vector<glm::dvec3> points = worldPoints();

    Fixture()
    {
        std::filesystem::create_directories(folder);
        configPath = (folder / "fuzz.toml").string();
        std::ofstream(configPath) << kConfig;
        std::vector<overlayd::ConfigProblem> problems;
        auto config = overlayd::loadConfigFile(configPath, problems);
        if (!config)
            std::abort(); // the fixed config must load
        live = config->camera;
    }
    ~Fixture() { std::filesystem::remove_all(folder); }
};

[[noreturn]] void fail(const std::string &why)
{
    std::fprintf(stderr, "save_roundtrip_fuzz: %s\n", why.c_str());
    std::abort();
}

// A point on a clipping boundary (the near or far plane, the scissor's edge) may fall either side of it after the
// save's 12-decimal rounding of the pose: that is the same camera, so only such a point may change its status.
bool onBoundary(const overlayd::ProjectedPoint &p, double nearDepth)
{
    constexpr double kEdge = 1e-9;
    if (p.status == overlayd::PointStatus::Clipped)
        return false;
    if (std::abs(p.depth - nearDepth) <= kEdge || std::abs(p.depth - 1.0) <= kEdge)
        return true;
    const double tolerance = kEdge * std::max(1.0, std::max(std::abs(p.pixel.x), std::abs(p.pixel.y)));
    return std::abs(p.pixel.x) <= tolerance || std::abs(p.pixel.y) <= tolerance ||
           std::abs(p.pixel.x - kWidth) <= tolerance || std::abs(p.pixel.y - kHeight) <= tolerance;
}

bool samePixel(const overlayd::ProjectedPoint &a, const overlayd::ProjectedPoint &b, double nearDepth)
{
    if (a.status != b.status)
        return onBoundary(a, nearDepth) || onBoundary(b, nearDepth);
    if (a.status == overlayd::PointStatus::Clipped)
        return true;
    const double tolerance = 1e-9 * std::max(1.0, std::max(std::abs(a.pixel.x), std::abs(a.pixel.y)));
    return std::abs(a.pixel.x - b.pixel.x) <= tolerance && std::abs(a.pixel.y - b.pixel.y) <= tolerance;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static Fixture fixture;
    const std::string_view body(reinterpret_cast<const char *>(data), size);
    auto changed = overlayd::cameraFromJson(body, fixture.live, kWidth, kHeight);
    if (!changed)
        return 0; // refused whole: nothing to save
    auto liveCamera = changed->build(kWidth, kHeight);
    if (!liveCamera)
        fail("an accepted change does not build: " + liveCamera.error().message);

    const std::string dropIn = overlayd::liveDropInPath(fixture.configPath);
    std::ofstream(dropIn, std::ios::trunc) << kEarlierDropIn;
    auto written = overlayd::writeLiveDropIn(fixture.configPath, *changed, "save_roundtrip_fuzz");
    if (!written)
        fail("the save failed: " + written.error().message);
    std::vector<overlayd::ConfigProblem> problems;
    auto loaded = overlayd::loadConfigFile(fixture.configPath, problems);
    if (!loaded)
        fail("the saved config does not load: " + loaded.error().message);
    auto savedCamera = loaded->camera.build(kWidth, kHeight);
    if (!savedCamera)
        fail("the saved camera does not build: " + savedCamera.error().message);
    const double nearDepth = changed->depth == overlayd::DepthRange::ZeroToOne ? 0.0 : -1.0;
    for (const glm::dvec3 &point : fixture.points) {
        const overlayd::ProjectedPoint a = liveCamera->project(point), b = savedCamera->project(point);
        if (!samePixel(a, b, nearDepth))
            fail("(" + std::to_string(point.x) + ", " + std::to_string(point.y) + ", " + std::to_string(point.z) +
                 ") projects to (" + std::to_string(a.pixel.x) + ", " + std::to_string(a.pixel.y) + ") live and to (" +
                 std::to_string(b.pixel.x) + ", " + std::to_string(b.pixel.y) + ") saved");
    }
    return 0;
}
