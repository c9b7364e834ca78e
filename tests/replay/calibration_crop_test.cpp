// SPDX-License-Identifier: Apache-2.0
// calibration_crop = [x, y, width, height] through the real binary: `overlayd project` of a 1280x720 stream made
// from an off-centre region of a 1600x1200 calibration lands where cv::projectPoints puts the points with the
// camera matrix transformed by hand; check-config refuses a region of another aspect at its file:line:column.
#include <cstdio>
#include <string>
#include <vector>

#include <opencv2/calib3d.hpp>

#include <gtest/gtest.h>

#include "harness.h"

namespace overlayd::test {
namespace {

std::string config(const std::string &crop)
{
    return "[source]\nkind = \"synthetic\"\nwidth = 1280\nheight = 720\n"
           "[camera]\nrvec = [0.1, -0.2, 0.05]\ntvec = [0.3, -0.1, 0.5]\ncalibration_crop = " +
           crop +
           "\n[camera.pinhole]\nfx = 1000\nfy = 990\ncx = 812.25\ncy = 640.75\nwidth = 1600\nheight = 1200\n"
           "[camera.distortion]\nmodel = \"plumb_bob\"\ncoefficients = [-0.1, 0.02, 0.001, -0.0005, 0.0]\n";
}

TEST(CalibrationCrop, ProjectMatchesOpenCVWithTheCroppedAndScaledCameraMatrix)
{
    const std::string dir = scratchDir("calibration-crop");
    writeFile(dir + "/crop.toml", config("[100, 300, 1200, 675]"));
    // s = 1280 / 1200; f' = f s; c' = (c + 0.5 - corner) s - 0.5 (pixel centres at integers).
    const double s = 1280.0 / 1200.0;
    const cv::Matx33d k(1000 * s, 0, (812.25 + 0.5 - 100) * s - 0.5, 0, 990 * s, (640.75 + 0.5 - 300) * s - 0.5, 0, 0,
                        1);
    const std::vector<cv::Point3d> world{{0.2, 0.1, 3}, {-0.5, 0.3, 4}, {0.4, -0.2, 2.5}, {0, 0, 6}};
    std::vector<cv::Point2d> expected;
    cv::projectPoints(world, cv::Vec3d(0.1, -0.2, 0.05), cv::Vec3d(0.3, -0.1, 0.5), k,
                      std::vector<double>{-0.1, 0.02, 0.001, -0.0005, 0.0}, expected);
    const RunResult run = runOverlayd("project --config crop.toml --json --" + pointArguments(world), dir);
    ASSERT_EQ(run.exitStatus, 0) << run.all();
    size_t at = 0;
    for (size_t i = 0; i < world.size(); ++i) {
        at = run.out.find("\"pixel\":[", at);
        ASSERT_NE(at, std::string::npos) << run.out;
        double u = NAN, v = NAN;
        std::sscanf(run.out.c_str() + at + 9, "%lf,%lf", &u, &v);
        EXPECT_NEAR(u, expected[i].x, 1e-6) << i << "\n" << run.out;
        EXPECT_NEAR(v, expected[i].y, 1e-6) << i << "\n" << run.out;
        ++at;
    }
}

TEST(CalibrationCrop, CheckConfigRefusesARegionOfAnotherAspectAtItsKey)
{
    const std::string dir = scratchDir("calibration-crop-bad");
    writeFile(dir + "/bad.toml", config("[100, 300, 1200, 700]"));
    const RunResult run = runOverlayd("check-config bad.toml", dir);
    EXPECT_EQ(run.exitStatus, 2) << run.all();
    EXPECT_NE(run.all().find("bad.toml:8:20: camera.calibration_crop: the region [100, 300, 1200, 700] is not of the "
                             "stream's aspect"),
              std::string::npos)
        << run.all();
}

} // namespace
} // namespace overlayd::test
