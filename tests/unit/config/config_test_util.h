// SPDX-License-Identifier: Apache-2.0
// Helpers shared by the config tests: loading TOML text, the problems as text, OpenCV's reference projection.
#pragma once

#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

#include "config/daemon_config.h"

namespace overlayd::test {

// A synthetic source and a camera: the least a config needs, for tests of the other sections.
inline const std::string kMinimalConfig = R"(
[source]
kind = "synthetic"
width = 640
height = 480
[camera]
position = [0.0, -6.0, 3.0]
yaw = 90.0
pitch = 25.0
fov = 60.0
)";

inline std::string sourceDir()
{
    return OVERLAYD_SOURCE_DIR;
}

// Every problem, one "file:line:column: key: message" per line, for failure messages.
inline std::string formatProblems(const std::vector<ConfigProblem> &problems)
{
    std::string all;
    for (const ConfigProblem &p : problems)
        all += p.format() + "\n";
    return all;
}

// Whether some problem is at `key` and its message holds `words`.
inline bool hasProblem(const std::vector<ConfigProblem> &problems, const std::string &key, const std::string &words)
{
    for (const ConfigProblem &p : problems)
        if (p.key == key && p.message.find(words) != std::string::npos)
            return true;
    return false;
}

// Loads text that must be valid; fails the test with every problem otherwise.
inline DaemonConfig loadValid(const std::string &text, const std::string &base = ".")
{
    std::vector<ConfigProblem> problems;
    auto config = loadConfigText(text, "test.toml", base, problems);
    const std::string all = formatProblems(problems);
    EXPECT_TRUE(config.ok()) << all;
    EXPECT_TRUE(problems.empty()) << all;
    return config ? config.value() : DaemonConfig{};
}

inline std::vector<ConfigProblem> loadInvalid(const std::string &text, const std::string &base = ".")
{
    std::vector<ConfigProblem> problems;
    auto config = loadConfigText(text, "test.toml", base, problems);
    EXPECT_FALSE(config.ok());
    if (!config.ok()) {
        EXPECT_EQ(config.error().code, ErrorCode::ConfigError);
    }
    return problems;
}

// cv::projectPoints of world points for x_optical = R x + t, K and distortion coefficients (plumb_bob/rational).
inline std::vector<cv::Point2d> opencvProject(const std::vector<cv::Point3d> &world, const cv::Matx33d &r,
                                              const cv::Vec3d &t, const cv::Matx33d &k, const std::vector<double> &d)
{
    cv::Vec3d rvec;
    cv::Rodrigues(r, rvec);
    std::vector<cv::Point2d> pixels;
    cv::projectPoints(world, rvec, t, k, d, pixels);
    return pixels;
}

} // namespace overlayd::test
