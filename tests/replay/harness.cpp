// SPDX-License-Identifier: Apache-2.0
// The replay tests' harness: processes, scratch folders and OpenCV's colour conversions.
#include "harness.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include <opencv2/imgproc.hpp>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

namespace overlayd::test {

namespace fs = std::filesystem;

std::string dataPath(const std::string &name)
{
    return std::string(OVERLAYD_SOURCE_DIR) + "/tests/data/replay/" + name;
}

std::string badConfigPath(const std::string &name)
{
    return std::string(OVERLAYD_SOURCE_DIR) + "/tests/data/config/bad/" + name;
}

std::string binary()
{
    return OVERLAYD_BINARY;
}

std::vector<std::string> binaryArgv()
{
    std::vector<std::string> words;
    std::string launcher = OVERLAYD_LAUNCHER;
    for (size_t start = 0; !launcher.empty() && start <= launcher.size();) {
        const size_t bar = std::min(launcher.find('|', start), launcher.size());
        words.push_back(launcher.substr(start, bar - start));
        start = bar + 1;
    }
    words.push_back(binary());
    return words;
}

std::string binaryCommand()
{
    std::string command;
    for (const std::string &word : binaryArgv())
        command += (command.empty() ? "'" : " '") + word + "'";
    return command;
}

namespace {

// The folders this process made, removed when it exits (they hold frames of megabytes, and a name per pid would
// otherwise pile up in /tmp); OVERLAYD_KEEP_SCRATCH=1 keeps them for a look after a failure.
struct ScratchFolders {
    std::vector<fs::path> made;
    ~ScratchFolders()
    {
        if (std::getenv("OVERLAYD_KEEP_SCRATCH") != nullptr)
            return;
        std::error_code ignored;
        for (const fs::path &dir : made)
            fs::remove_all(dir, ignored);
    }
};
ScratchFolders scratchFolders;

} // namespace

std::string scratchDir(const std::string &name)
{
    // The pid too: other builds' replay tests (a sanitizer build, a cross build under qemu) may run at the same
    // time on the machine, and a shared folder would be emptied under a running test.
    const fs::path dir =
        fs::path(::testing::TempDir()) / ("overlayd-replay-" + name + "-" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    scratchFolders.made.push_back(dir);
    return dir.string();
}

std::vector<uint8_t> readFile(const std::string &path)
{
    std::ifstream in(path, std::ios::binary);
    return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), {});
}

std::string pointArguments(const std::vector<cv::Point3d> &points)
{
    std::string args;
    char number[96];
    for (const cv::Point3d &p : points) {
        std::snprintf(number, sizeof number, " %.17g %.17g %.17g", p.x, p.y, p.z);
        args += number;
    }
    return args;
}

void writeFile(const std::string &path, const std::string &text)
{
    std::ofstream(path, std::ios::binary) << text;
}

RunResult runOverlayd(const std::string &args, const std::string &dir)
{
    const std::string command =
        "cd '" + dir + "' && " + binaryCommand() + " " + args + " > overlayd.stdout 2> overlayd.stderr";
    const int status = std::system(command.c_str());
    RunResult result;
    if (WIFEXITED(status))
        result.exitStatus = WEXITSTATUS(status);
    // The shell reports a child killed by signal N as exit status 128 + N.
    result.crashed = WIFSIGNALED(status) || (WIFEXITED(status) && WEXITSTATUS(status) > 128);
    const auto out = readFile(dir + "/overlayd.stdout"), err = readFile(dir + "/overlayd.stderr");
    result.out.assign(out.begin(), out.end());
    result.err.assign(err.begin(), err.end());
    return result;
}

size_t rawFrameSize(const std::string &format, int width, int height)
{
    const size_t pixels = size_t(width) * height;
    if (format == "YUYV" || format == "UYVY")
        return pixels * 2;
    if (format == "NV12" || format == "YUV420")
        return pixels * 3 / 2;
    if (format == "RGB24" || format == "BGR24")
        return pixels * 3;
    return pixels; // GREY
}

cv::Mat rawToBgr(const std::vector<uint8_t> &bytes, size_t offset, const std::string &format, int width, int height)
{
    uint8_t *data = const_cast<uint8_t *>(bytes.data()) + offset;
    cv::Mat bgr;
    if (format == "YUYV")
        cv::cvtColor(cv::Mat(height, width, CV_8UC2, data), bgr, cv::COLOR_YUV2BGR_YUYV);
    else if (format == "UYVY")
        cv::cvtColor(cv::Mat(height, width, CV_8UC2, data), bgr, cv::COLOR_YUV2BGR_UYVY);
    else if (format == "NV12")
        cv::cvtColor(cv::Mat(height * 3 / 2, width, CV_8UC1, data), bgr, cv::COLOR_YUV2BGR_NV12);
    else if (format == "YUV420")
        cv::cvtColor(cv::Mat(height * 3 / 2, width, CV_8UC1, data), bgr, cv::COLOR_YUV2BGR_I420);
    else if (format == "RGB24")
        cv::cvtColor(cv::Mat(height, width, CV_8UC3, data), bgr, cv::COLOR_RGB2BGR);
    else if (format == "BGR24")
        bgr = cv::Mat(height, width, CV_8UC3, data).clone();
    else
        cv::cvtColor(cv::Mat(height, width, CV_8UC1, data), bgr, cv::COLOR_GRAY2BGR);
    return bgr;
}

cv::Mat renderFrameBgr(const std::string &config, const std::string &format, int width, int height,
                       const std::string &dir, int frames, int index)
{
    const RunResult run =
        runOverlayd("render --config '" + config + "' --frames " + std::to_string(frames) + " --output out.raw", dir);
    EXPECT_EQ(run.exitStatus, 0) << run.all();
    const std::vector<uint8_t> bytes = readFile(dir + "/out.raw");
    const size_t frameSize = rawFrameSize(format, width, height);
    EXPECT_EQ(bytes.size(), frameSize * frames) << "raw output of " << config;
    if (bytes.size() < frameSize * (index + 1))
        return {};
    return rawToBgr(bytes, frameSize * index, format, width, height);
}

} // namespace overlayd::test
