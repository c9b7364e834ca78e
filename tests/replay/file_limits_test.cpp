// SPDX-License-Identifier: Apache-2.0
// Files the daemon reads (issue 19, classes 2 and 5), through the real binary: a config or calibration path that is
// a directory, a FIFO with no writer or a device, a config over the size limit, a calibration nested deeper than
// the parsers can take, a declared matrix far larger than its field, a ROS distortion that is not a list, a
// 2-channel OpenCV matrix, a key given twice, and a Y4M replay whose header declares an enormous frame. check-config
// exits 2 naming the file (and the line where it is the file's fault); nothing crashes, blocks or allocates
// what the file asks for.
#include <chrono>
#include <string>

#include <sys/stat.h>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "harness.h"

namespace overlayd::test {
namespace {

// ROS camera_info at its shortest (rows, cols and the model are optional).
const std::string kRosHead =
    "image_width: 640\nimage_height: 480\ncamera_matrix:\n  data: [510.5, 0.25, 322.1, 0, 508.2, 241.7, 0, 0, 1]\n";

const std::string kOpenCvHead = "%YAML:1.0\n"
                                "---\n"
                                "image_width: 640\n"
                                "image_height: 480\n"
                                "camera_matrix: !!opencv-matrix\n"
                                "   rows: 3\n"
                                "   cols: 3\n"
                                "   dt: d\n"
                                "   data: [ 510.5, 0.25, 322.1, 0.0, 508.2, 241.7, 0.0, 0.0, 1.0 ]\n";

// A config in `dir` whose camera reads `calibration`.
void writeCalibratedConfig(const std::string &dir, const std::string &calibration)
{
    writeFile(dir + "/cam.toml",
              "[source]\nkind = \"synthetic\"\nwidth = 640\nheight = 480\n[camera]\ncalibration = \"" + calibration +
                  "\"\nrvec = [0, 0, 0]\ntvec = [0, 0, 0]\n");
}

void expectRefused(const RunResult &run, const std::string &message)
{
    EXPECT_FALSE(run.crashed) << run.all();
    EXPECT_EQ(run.exitStatus, 2) << run.all();
    EXPECT_NE(run.all().find(message), std::string::npos) << "expected '" << message << "' in:\n" << run.all();
}

// check-config on a config whose calibration file holds `text`.
RunResult checkCalibration(const std::string &test, const std::string &name, const std::string &text)
{
    const std::string dir = scratchDir(test);
    writeFile(dir + "/" + name, text);
    writeCalibratedConfig(dir, name);
    return runOverlayd("check-config cam.toml", dir);
}

TEST(FileLimits, ADirectoryAsTheConfigIsRefused)
{
    const std::string dir = scratchDir("limits-config-dir");
    ASSERT_EQ(::mkdir((dir + "/conf.toml").c_str(), 0755), 0);
    expectRefused(runOverlayd("check-config conf.toml", dir),
                  "conf.toml:0:0: the config file is a directory, not a regular file");
}

TEST(FileLimits, AConfigOverOneMebibyteIsRefusedUnread)
{
    const std::string dir = scratchDir("limits-config-big");
    writeFile(dir + "/big.toml", "[source]\nkind = \"synthetic\"\n# " + std::string(2u << 20, 'x') + "\n");
    expectRefused(runOverlayd("check-config big.toml", dir), "bytes; at most 1048576 are read");
}

// Without the pre-scan, toml++ overflows the stack on this (exit by SIGSEGV). Under [source], the key's 64th part
// is the 65th level.
TEST(FileLimits, DeepDottedKeysInTheConfigAreRefused)
{
    const std::string dir = scratchDir("limits-config-deep");
    std::string key = "a";
    for (int i = 0; i < 100000; ++i)
        key += ".b";
    writeFile(dir + "/deep.toml", "[source]\nkind = \"synthetic\"\n" + key + " = 1\n");
    expectRefused(runOverlayd("check-config deep.toml", dir), "deep.toml:3:126: nested deeper than 64 levels");
}

// An ordinary open() of a FIFO with no writer blocks until one comes: this run returns.
TEST(FileLimits, AFifoAsTheCalibrationIsRefusedWithoutBlocking)
{
    const std::string dir = scratchDir("limits-calibration-fifo");
    ASSERT_EQ(::mkfifo((dir + "/cal.yaml").c_str(), 0600), 0);
    writeCalibratedConfig(dir, "cal.yaml");
    expectRefused(runOverlayd("check-config cam.toml", dir), "cal.yaml is a FIFO, not a regular file");
}

TEST(FileLimits, ADeviceAsTheCalibrationIsCalledADevice)
{
    const std::string dir = scratchDir("limits-calibration-device");
    writeCalibratedConfig(dir, "/dev/zero");
    expectRefused(runOverlayd("check-config cam.toml", dir),
                  "calibration file /dev/zero is a character device, not a regular file");
}

// cv::FileStorage overflows the stack on this (a crash without the pre-scan).
TEST(FileLimits, ADeeplyNestedCalibrationIsRefusedAtItsLine)
{
    expectRefused(checkCalibration("limits-calibration-deep", "deep.yaml",
                                   kOpenCvHead + "extra: " + std::string(100000, '[') + "\n"),
                  "deep.yaml:10: nested deeper than 64 levels");
}

// `>> cv::Mat` allocates rows x cols before it reads the data: 20 GB here.
TEST(FileLimits, AHugeDeclaredMatrixIsRefusedByItsSize)
{
    expectRefused(checkCalibration("limits-calibration-huge", "huge.yaml",
                                   kOpenCvHead + "distortion_coefficients: !!opencv-matrix\n   rows: 50000\n   cols: "
                                                 "50000\n   dt: d\n   data: [ 1, 2 ]\n"),
                  "huge.yaml:10: distortion_coefficients: 50000x50000; it must be 1xN or Nx1");
}

TEST(FileLimits, ATwoChannelOpenCvMatrixIsRefused)
{
    expectRefused(checkCalibration("limits-calibration-2ch", "two.yaml",
                                   kOpenCvHead +
                                       "distortion_coefficients: !!opencv-matrix\n   rows: 1\n   cols: 4\n"
                                       "   dt: \"2d\"\n   data: [ -0.1, 0.5, 0.01, 0.5, 0.001, 0.5, 0.0, 0.5 ]\n"),
                  "two.yaml:10: distortion_coefficients: dt must be one single-channel type");
}

// Was silently dropped: the camera ran without distortion.
TEST(FileLimits, ARosDistortionThatIsNotAListIsRefused)
{
    expectRefused(checkCalibration("limits-calibration-ros", "ros.yaml",
                                   kRosHead + "distortion_coefficients:\n  rows: 1\n  cols: 5\n  data: -0.1\n"),
                  "ros.yaml:8: distortion_coefficients.data: expected a list of numbers");
}

TEST(FileLimits, AKeyGivenTwiceInACalibrationIsRefused)
{
    expectRefused(checkCalibration("limits-calibration-dup", "dup.yaml", kRosHead + "image_width: 1280\n"),
                  "dup.yaml:5: 'image_width' given twice (first on line 1)");
}

// 16384 x 16384 at 4:4:4 is 768 MiB a frame: refused from the header (it was allocated, several times over).
TEST(FileLimits, AY4mDeclaringAnEnormousFrameIsRefusedFromItsHeader)
{
    const std::string dir = scratchDir("limits-y4m-huge");
    writeFile(dir + "/huge.y4m", "YUV4MPEG2 W16384 H16384 F30:1 C444\nFRAME\nabc");
    writeFile(dir + "/replay.toml", "[source]\nkind = \"replay\"\nfps = 30.0\n[source.replay]\npath = \"huge.y4m\"\n"
                                    "format = \"y4m\"\n");
    const RunResult run = runOverlayd("render --config replay.toml --frames 1 --output out.y4m", dir);
    EXPECT_FALSE(run.crashed) << run.all();
    EXPECT_EQ(run.exitStatus, 1) << run.all();
    EXPECT_NE(run.err.find("huge.y4m: Y4M header: 16384x16384 C444 is 805306368 bytes a frame, over the limit of "
                           "268435456"),
              std::string::npos)
        << run.err;
}

TEST(FileLimits, ADirectoryAsAReplayIsCalledADirectory)
{
    const std::string dir = scratchDir("limits-replay-dir");
    ASSERT_EQ(::mkdir((dir + "/dir.y4m").c_str(), 0755), 0);
    writeFile(dir + "/replay.toml", "[source]\nkind = \"replay\"\nfps = 30.0\n[source.replay]\npath = \"dir.y4m\"\n"
                                    "format = \"y4m\"\n");
    const RunResult run = runOverlayd("render --config replay.toml --frames 1 --output out.y4m", dir);
    EXPECT_FALSE(run.crashed) << run.all();
    EXPECT_EQ(run.exitStatus, 2) << run.all(); // known from the config, as check-config knows it
    EXPECT_NE(run.err.find("dir.y4m: is a directory, not a regular file"), std::string::npos) << run.err;
}

// Each image annotation is within its limits, their sum is not: 200 annotations of one small PNG (a 4096 x 4096
// image, 64 MiB decoded) are refused at the fifth, which takes the scene past kMaxSceneImageBytes (256 MiB), by
// check-config, render and run alike with the same line, quickly (the file is decoded once, the fifth never).
TEST(FileLimits, ManyImageAnnotationsAreBoundedAsAWhole)
{
    const std::string dir = scratchDir("image-total");
    ASSERT_TRUE(cv::imwrite(dir + "/big.png", cv::Mat(4096, 4096, CV_8UC1, cv::Scalar(0))));
    std::string config = "[source]\nkind = \"synthetic\"\nwidth = 64\nheight = 48\n";
    for (int i = 0; i < 200; ++i) // annotation[i].path on line 7 + 4 i
        config += "[[annotation]]\ntype = \"image\"\npath = \"big.png\"\nposition = [0, 0]\n";
    writeFile(dir + "/big.toml", config);
    const std::string expected = "big.toml:23:8: annotation[4].path: the image ";
    for (const std::string &args :
         {std::string("check-config big.toml"), std::string("render --config big.toml --frames 1 --output out.y4m"),
          std::string("run --config big.toml --frames 1")}) {
        SCOPED_TRACE(args);
        const auto start = std::chrono::steady_clock::now();
        const RunResult run = runOverlayd(args, dir);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        EXPECT_FALSE(run.crashed) << run.all();
        EXPECT_EQ(run.exitStatus, 2) << run.all();
        EXPECT_NE(run.all().find(expected), std::string::npos) << run.all();
        EXPECT_NE(run.all().find("past 256 MiB"), std::string::npos) << run.all();
        EXPECT_LT(seconds, 20.0) << "one decode of 64 MiB takes well under a second";
    }
}

} // namespace
} // namespace overlayd::test
