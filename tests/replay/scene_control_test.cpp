// SPDX-License-Identifier: Apache-2.0
// The running scene changes through SceneControl: `overlayd run` on one pose, the config swapped for another pose and
// reloaded with SIGHUP, and the marker on the world origin must sit where `overlayd project` puts it for each pose:
// before the reload in the first frames, after it in the last ones. The projection and the rasterizer are checked
// against the independent `project` path, and the source must not be re-opened for a camera change.
#include <csignal>
#include <filesystem>
#include <regex>

#include <sys/wait.h>

#include <gtest/gtest.h>

#include "harness.h"
#include "process.h"

namespace overlayd::test {
namespace {

namespace fs = std::filesystem;

constexpr int kWidth = 160, kHeight = 120;
constexpr size_t kFrameBytes = size_t(kWidth) * kHeight; // GREY

// The pixel `overlayd project --json` gives the world origin.
cv::Point2d projectedOrigin(const std::string &config, const std::string &dir)
{
    const RunResult run = runOverlayd("project --config '" + config + "' --json -- 0 0 0", dir);
    std::smatch match;
    const std::regex pixel(R"("pixel":\[([-0-9.e]+),([-0-9.e]+)\])");
    if (run.exitStatus != 0 || !std::regex_search(run.out, match, pixel)) {
        ADD_FAILURE() << run.all();
        return {-1, -1};
    }
    return {std::stod(match[1]), std::stod(match[2])};
}

// The centroid of the dark marker's pixels on the white frame; (-1, -1) when there are none.
cv::Point2d markerCentroid(const std::vector<uint8_t> &bytes, size_t frame)
{
    double sx = 0, sy = 0;
    int count = 0;
    for (size_t i = 0; i < kFrameBytes; ++i)
        if (bytes[frame * kFrameBytes + i] < 100) {
            sx += double(i % kWidth);
            sy += double(i / kWidth);
            ++count;
        }
    return count ? cv::Point2d(sx / count, sy / count) : cv::Point2d(-1, -1);
}

TEST(SceneControl, ReloadedPoseMovesTheMarkerWhereProjectSays)
{
    const std::string dir = scratchDir("scene-control");
    const cv::Point2d before = projectedOrigin(dataPath("scene_pose_a.toml"), dir);
    const cv::Point2d after = projectedOrigin(dataPath("scene_pose_b.toml"), dir);
    ASSERT_GT(cv::norm(after - before), 10.0) << "the two poses must put the origin far apart";

    const std::string config = dir + "/overlayd.toml";
    fs::copy_file(dataPath("scene_pose_a.toml"), config);
    const pid_t pid = startDaemon(dir, "overlayd.toml");
    ASSERT_GT(pid, 0);
    const auto frames = [&] {
        std::error_code error;
        const auto size = fs::file_size(dir + "/out.raw", error);
        return error ? 0 : size / kFrameBytes;
    };
    EXPECT_TRUE(waitFor([&] { return frames() >= 5; })) << fileText(dir + "/overlayd.stderr");
    fs::copy_file(dataPath("scene_pose_b.toml"), config, fs::copy_options::overwrite_existing);
    kill(pid, SIGHUP);
    EXPECT_TRUE(waitFor([&] { return fileText(dir + "/overlayd.stderr").find("reloaded") != std::string::npos; }));
    const auto reloadedAt = frames();
    EXPECT_TRUE(waitFor([&] { return frames() >= reloadedAt + 5; })) << fileText(dir + "/overlayd.stderr");
    kill(pid, SIGTERM);
    int status = 0;
    ASSERT_EQ(waitpid(pid, &status, 0), pid);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);

    const std::string log = fileText(dir + "/overlayd.stderr");
    EXPECT_EQ(log.find("source re-opened"), std::string::npos) << log;
    const std::vector<uint8_t> bytes = readFile(dir + "/out.raw");
    const size_t count = bytes.size() / kFrameBytes;
    ASSERT_GE(count, 10u);
    // A 1 px plus rasterized without anti-aliasing: its centroid is the projected point to within half a pixel.
    const cv::Point2d first = markerCentroid(bytes, 0), last = markerCentroid(bytes, count - 1);
    EXPECT_LT(cv::norm(first - before), 0.75) << first << " vs project " << before;
    EXPECT_LT(cv::norm(last - after), 0.75) << last << " vs project " << after;
}

} // namespace
} // namespace overlayd::test
