// SPDX-License-Identifier: Apache-2.0
// A reload is a transaction (issue 19): a SIGHUP whose new config cannot be carried out whole (a source that cannot
// be opened, a sink that cannot be created, both at once with a new camera and overlay) is refused, the log says
// why, and the old config keeps streaming with its old overlay; a good reload afterwards still switches.
#include <csignal>
#include <filesystem>
#include <fstream>
#include <ostream>

#include <sys/wait.h>

#include <gtest/gtest.h>

#include "harness.h"
#include "process.h"

namespace overlayd::test {
namespace {

namespace fs = std::filesystem;

// 160x120 YUYV in a Y4M file: 4:2:2 planes, after "FRAME\n".
constexpr size_t kFrameBytes = 160 * 120 * 2;
constexpr size_t kFrameRecord = kFrameBytes + 6;

// A plain white frame (one checker wider than the frame): a static picture, so that every frame with the same
// overlay is byte for byte the same.
const std::string kWhiteSource = "[source]\nkind = \"synthetic\"\nformat = \"YUYV\"\nwidth = 160\nheight = 120\n"
                                 "fps = 30.0\n[source.synthetic]\npattern = \"checkerboard\"\nchecker_px = 16384\n";
const std::string kCamera = "[camera]\neye = [0.0, -6.0, 4.0]\ntarget = [0.0, 0.0, 0.0]\nup = [0.0, 0.0, 1.0]\n"
                            "fov = 60.0\n";
const std::string kMovedCamera = "[camera]\neye = [3.0, -5.0, 2.0]\ntarget = [0.0, 0.0, 0.0]\nup = [0.0, 0.0, 1.0]\n"
                                 "fov = 40.0\n";

// A filled rectangle where `at` says, and a marker on the world origin (so that the camera shows in the pixels).
std::string overlay(const std::string &at)
{
    return "[[annotation]]\ntype = \"rect\"\nposition = " + at +
           "\nsize = [40.0, 30.0]\nfilled = true\nstyle = { colour = \"black\" }\n"
           "[[annotation]]\ntype = \"markers\"\npoints = [[0.0, 0.0, 0.0]]\nmarker = \"plus\"\nsize_px = 11\n"
           "style = { colour = \"black\", width = 1.0, antialias = false }\n";
}

std::string sink(const std::string &path)
{
    return "[[sink]]\nkind = \"y4m\"\npath = \"" + path + "\"\n";
}

std::string configText(const std::string &source, const std::string &camera, const std::string &at,
                       const std::string &sinks)
{
    return "[daemon]\nstats_interval = 0.0\n" + source + camera + overlay(at) + sinks;
}

const std::string kGood = configText(kWhiteSource, kCamera, "[20.0, 20.0]", sink("a.y4m"));

struct BadReload {
    const char *name;
    std::string config;
    const char *why; // what the refusal must name
};

void PrintTo(const BadReload &value, std::ostream *out)
{
    *out << value.name;
}

const std::string kMissingReplay = "[source]\nkind = \"replay\"\n[source.replay]\npath = \"missing.y4m\"\n";
const std::string kNotY4m = "[source]\nkind = \"replay\"\n[source.replay]\npath = \"garbage.y4m\"\n";
// A pinhole calibrated at 4:3 for a 16:9 stream, without calibration_crop: the camera cannot be built for the
// stream, which only opening the synthetic scene source finds out.
const std::string kImpossibleSynthetic =
    "[source]\nkind = \"synthetic\"\nformat = \"YUYV\"\nwidth = 160\nheight = 90\nfps = 30.0\n"
    "[source.synthetic]\npattern = \"checkerboard-scene\"\n";
const std::string kFourThreeCamera =
    "[camera]\neye = [0.0, -6.0, 4.0]\ntarget = [0.0, 0.0, 0.0]\nup = [0.0, 0.0, 1.0]\n"
    "[camera.pinhole]\nfx = 100.0\nfy = 100.0\ncx = 79.5\ncy = 59.5\nwidth = 160\n"
    "height = 120\n";

// The last whole frame in a Y4M file (empty when there is none), read from its end: the file grows while we look.
std::string lastFrame(const std::string &path)
{
    std::ifstream in(path, std::ios::binary);
    std::string header;
    if (!std::getline(in, header))
        return {};
    std::error_code error;
    const size_t size = fs::file_size(path, error);
    if (error || size < header.size() + 1 + kFrameRecord)
        return {};
    const size_t frames = (size - header.size() - 1) / kFrameRecord;
    std::string frame(kFrameBytes, '\0');
    in.seekg(std::streamoff(header.size() + 1 + (frames - 1) * kFrameRecord + 6));
    in.read(frame.data(), std::streamsize(kFrameBytes));
    return in ? frame : std::string();
}

// The daemon under test, killed if a failed assertion leaves it running.
struct Daemon {
    pid_t pid;
    ~Daemon()
    {
        if (pid > 0 && waitpid(pid, nullptr, WNOHANG) == 0) {
            kill(pid, SIGKILL);
            waitpid(pid, nullptr, 0);
        }
    }
};

class RefusedReload : public ::testing::TestWithParam<BadReload>
{};

TEST_P(RefusedReload, KeepsStreamingWithTheOldOverlayAndSaysWhy)
{
    const BadReload bad = GetParam();
    const std::string dir = scratchDir(std::string("reload-") + bad.name);
    const std::string config = dir + "/overlayd.toml";
    const std::string log = dir + "/overlayd.stderr";
    writeFile(config, kGood);
    writeFile(dir + "/garbage.y4m", "this is not a Y4M file\n");
    writeFile(dir + "/not-a-folder", "a sink path under this file cannot be created\n");
    const Daemon daemon{startDaemon(dir, "overlayd.toml")};
    const pid_t pid = daemon.pid;
    ASSERT_GT(pid, 0);
    const auto size = [&](const char *name) {
        std::error_code error;
        const auto bytes = fs::file_size(dir + "/" + name, error);
        return error ? 0 : bytes;
    };
    ASSERT_TRUE(waitFor([&] { return size("a.y4m") > 10 * kFrameRecord; })) << fileText(log);
    const std::string oldOverlay = lastFrame(dir + "/a.y4m");
    ASSERT_EQ(oldOverlay.size(), kFrameBytes);

    writeFile(config, bad.config);
    kill(pid, SIGHUP);
    EXPECT_TRUE(waitFor([&] { return fileText(log).find("reload refused") != std::string::npos; })) << fileText(log);
    const std::string afterBad = fileText(log);
    const size_t refusal = afterBad.find("reload refused");
    ASSERT_NE(refusal, std::string::npos);
    const std::string refusalLine = afterBad.substr(refusal, afterBad.find('\n', refusal) - refusal);
    EXPECT_NE(refusalLine.find(bad.why), std::string::npos) << refusalLine;
    EXPECT_EQ(afterBad.find("reloaded"), std::string::npos) << afterBad;
    EXPECT_EQ(afterBad.find("NO SIGNAL"), std::string::npos) << afterBad;
    EXPECT_EQ(afterBad.find("source lost"), std::string::npos) << afterBad;

    // Frames keep flowing into the old sink, with the old overlay.
    const auto sizeAfterBad = size("a.y4m");
    EXPECT_TRUE(waitFor([&] { return size("a.y4m") > sizeAfterBad + 10 * kFrameRecord; }))
        << "the old config stopped streaming\n"
        << fileText(log);
    EXPECT_TRUE(lastFrame(dir + "/a.y4m") == oldOverlay) << "the overlay changed after a refused reload";
    EXPECT_FALSE(fs::exists(dir + "/b.y4m"));
    EXPECT_EQ(waitpid(pid, nullptr, WNOHANG), 0) << "the daemon exited";

    // A good reload afterwards switches: the rectangle moves, into a new file.
    writeFile(config, configText(kWhiteSource, kCamera, "[80.0, 40.0]", sink("c.y4m")));
    kill(pid, SIGHUP);
    EXPECT_TRUE(waitFor([&] { return size("c.y4m") > 10 * kFrameRecord; })) << fileText(log);
    const std::string newOverlay = lastFrame(dir + "/c.y4m");
    EXPECT_EQ(newOverlay.size(), kFrameBytes);
    EXPECT_FALSE(newOverlay == oldOverlay) << "the good reload did not change the overlay";

    kill(pid, SIGTERM);
    int status = 0;
    ASSERT_EQ(waitpid(pid, &status, 0), pid);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 0);
    EXPECT_NE(fileText(log).find("reloaded overlayd.toml"), std::string::npos) << fileText(log);
}

INSTANTIATE_TEST_SUITE_P(
    Configs, RefusedReload,
    ::testing::Values(
        BadReload{"missing_replay", configText(kMissingReplay, kCamera, "[20.0, 20.0]", sink("a.y4m")), "missing.y4m"},
        BadReload{"not_y4m", configText(kNotY4m, kCamera, "[20.0, 20.0]", sink("a.y4m")), "garbage.y4m"},
        BadReload{"impossible_synthetic",
                  configText(kImpossibleSynthetic, kFourThreeCamera, "[20.0, 20.0]", sink("a.y4m")), "aspect"},
        BadReload{"sink_that_cannot_be_created",
                  configText(kWhiteSource, kCamera, "[20.0, 20.0]", sink("a.y4m") + sink("not-a-folder/b.y4m")),
                  "not-a-folder/b.y4m"},
        BadReload{"source_sinks_and_camera_at_once",
                  configText(kMissingReplay, kMovedCamera, "[60.0, 50.0]", sink("b.y4m") + sink("not-a-folder/c.y4m")),
                  "missing.y4m"}), // the loader finds the missing replay first, before any source is opened
    [](const auto &param) { return std::string(param.param.name); });

} // namespace
} // namespace overlayd::test
