// SPDX-License-Identifier: Apache-2.0
// The replay tests' harness: runs the real `overlayd` binary in a scratch folder and reads what it wrote.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace overlayd::test {

struct RunResult {
    int exitStatus = -1;  // the process's exit status; -1 when it did not exit normally
    bool crashed = false; // killed by a signal (a crash, or a sanitizer abort)
    std::string out, err; // stdout and stderr
    std::string all() const { return out + err; }
};

// tests/data/replay/<name> and tests/data/config/bad/<name> in the source tree.
std::string dataPath(const std::string &name);
std::string badConfigPath(const std::string &name);
std::string binary();
// What starts the binary: the emulator's words first in a cross build (qemu-aarch64 -L SYSROOT), then binary().
std::vector<std::string> binaryArgv();
// The same, single-quoted for a shell command line.
std::string binaryCommand();

// A fresh, empty folder for one test under the test's temporary directory.
std::string scratchDir(const std::string &name);

// `overlayd ARGS` (a shell-quoted string) with the working directory `dir`.
RunResult runOverlayd(const std::string &args, const std::string &dir);

// Renders `frames` frames of a config to a raw file in dir and returns frame `index` converted to BGR by OpenCV
// (an independent converter: BT.601 limited range, the configs' colorimetry).
cv::Mat renderFrameBgr(const std::string &config, const std::string &format, int width, int height,
                       const std::string &dir, int frames = 1, int index = 0);
cv::Mat rawToBgr(const std::vector<uint8_t> &bytes, size_t offset, const std::string &format, int width, int height);
size_t rawFrameSize(const std::string &format, int width, int height);

// " x y z x y z ...": points as command-line arguments, each number exact (%.17g).
std::string pointArguments(const std::vector<cv::Point3d> &points);

std::vector<uint8_t> readFile(const std::string &path);
void writeFile(const std::string &path, const std::string &text);

} // namespace overlayd::test
