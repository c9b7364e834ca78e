// SPDX-License-Identifier: Apache-2.0
// ffprobe (Debian's ffmpeg, an independent Y4M reader) reads our Y4M output and agrees on size, pixel format and
// frame count.
#include <cstdio>
#include <memory>

#include <ostream>

#include <gtest/gtest.h>

#include "harness.h"

namespace overlayd::test {
namespace {

std::string ffprobe(const std::string &path)
{
    const std::string command = "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
                                "stream=width,height,pix_fmt,nb_read_frames -of compact=p=0 '" +
                                path + "' 2>&1";
    std::unique_ptr<FILE, int (*)(FILE *)> pipe(popen(command.c_str(), "r"), pclose);
    std::string output;
    char buffer[256];
    while (pipe && std::fgets(buffer, sizeof(buffer), pipe.get()))
        output += buffer;
    return output;
}

struct Case {
    const char *scene;
    const char *pixFmt; // what ffprobe must call it
};

// Names the case in test listings (CTest shows it) instead of its bytes.
void PrintTo(const Case &value, std::ostream *out)
{
    *out << value.scene;
}

class Ffprobe : public ::testing::TestWithParam<Case>
{};

TEST_P(Ffprobe, AgreesOnSizeFormatAndFrameCount)
{
    const Case c = GetParam();
    const std::string dir = scratchDir(std::string("ffprobe-") + c.scene);
    const RunResult run = runOverlayd(
        "render --config '" + dataPath(std::string(c.scene) + ".toml") + "' --frames 7 --output out.y4m", dir);
    ASSERT_EQ(run.exitStatus, 0) << run.all();
    EXPECT_EQ(ffprobe(dir + "/out.y4m"),
              std::string("width=320|height=240|pix_fmt=") + c.pixFmt + "|nb_read_frames=7\n");
}

INSTANTIATE_TEST_SUITE_P(Formats, Ffprobe,
                         ::testing::Values(Case{"persp_yuyv_top_left", "yuv422p"},
                                           Case{"persp_nv12_bottom_left", "yuv420p"},
                                           Case{"ortho_yuv420_top_left", "yuv420p"},
                                           Case{"distorted_grey_bottom_left", "gray"}),
                         [](const auto &param) { return std::string(param.param.scene); });

} // namespace
} // namespace overlayd::test
