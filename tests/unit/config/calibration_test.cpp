// SPDX-License-Identifier: Apache-2.0
// Calibration import: OpenCV YAML and XML written here with cv::FileStorage, ROS camera_info YAML written by hand;
// `calibration = "path"` in [camera] with TOML values overriding the file; missing and malformed files.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "config/calibration.h"
#include "config_test_util.h"

namespace overlayd::test {
namespace {

class CalibrationTest : public ::testing::Test
{
protected:
    void SetUp() override
    {
        dir_ =
            std::filesystem::temp_directory_path() / ("overlayd-calibration-" + std::to_string(::getpid()) + "-" +
                                                      ::testing::UnitTest::GetInstance()->current_test_info()->name());
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }

    std::string path(const std::string &name) const { return (dir_ / name).string(); }

    void writeOpenCv(const std::string &name, const std::vector<double> &d) const
    {
        cv::FileStorage fs(path(name), cv::FileStorage::WRITE);
        fs << "image_width" << 640 << "image_height" << 480;
        fs << "camera_matrix" << cv::Mat(cv::Matx33d(510.5, 0.25, 322.1, 0, 508.2, 241.7, 0, 0, 1));
        fs << "distortion_coefficients" << cv::Mat(d).t();
    }

    void writeText(const std::string &name, const std::string &text) const { std::ofstream(path(name)) << text; }

    std::filesystem::path dir_;
};

void expectIntrinsics(const Calibration &c)
{
    EXPECT_DOUBLE_EQ(c.pinhole.fx, 510.5);
    EXPECT_DOUBLE_EQ(c.pinhole.fy, 508.2);
    EXPECT_DOUBLE_EQ(c.pinhole.cx, 322.1);
    EXPECT_DOUBLE_EQ(c.pinhole.cy, 241.7);
    EXPECT_DOUBLE_EQ(c.pinhole.skew, 0.25);
    EXPECT_EQ(c.pinhole.width, 640);
    EXPECT_EQ(c.pinhole.height, 480);
}

TEST_F(CalibrationTest, OpenCvYaml)
{
    writeOpenCv("cam.yaml", {-0.1, 0.02, 0.001, 0.002, -0.003});
    auto c = loadCalibration(path("cam.yaml"));
    ASSERT_TRUE(c.ok()) << c.error().message;
    expectIntrinsics(*c);
    EXPECT_EQ(c->distortion.model, DistortionModel::RadialTangential);
    EXPECT_DOUBLE_EQ(c->distortion.coeffs[4], -0.003);
}

TEST_F(CalibrationTest, OpenCvXmlWithEightCoefficients)
{
    writeOpenCv("cam.xml", {-0.1, 0.02, 0.001, 0.002, -0.003, 0.01, 0.002, 0.0005});
    auto c = loadCalibration(path("cam.xml"));
    ASSERT_TRUE(c.ok()) << c.error().message;
    expectIntrinsics(*c);
    EXPECT_EQ(c->distortion.model, DistortionModel::Rational);
    EXPECT_DOUBLE_EQ(c->distortion.coeffs[7], 0.0005);
}

const char *kRosYaml = R"(image_width: 640
image_height: 480
camera_name: narrow_stereo
camera_matrix:
  rows: 3
  cols: 3
  data: [510.5, 0.25, 322.1, 0, 508.2, 241.7, 0, 0, 1]
distortion_model: %s
distortion_coefficients:
  rows: 1
  cols: %d
  data: [%s]
rectification_matrix:
  rows: 3
  cols: 3
  data: [1, 0, 0, 0, 1, 0, 0, 0, 1]
)";

std::string rosYaml(const char *model, int count, const char *data)
{
    char text[1024];
    std::snprintf(text, sizeof text, kRosYaml, model, count, data);
    return text;
}

TEST_F(CalibrationTest, RosCameraInfoModels)
{
    writeText("plumb.yaml", rosYaml("plumb_bob", 5, "-0.1, 0.02, 0.001, 0.002, 0.0"));
    writeText("fisheye.yml", rosYaml("equidistant", 4, "0.05, -0.01, 0.002, -0.0005"));
    writeText("rational.yaml", rosYaml("rational_polynomial", 8, "-0.1, 0.02, 0, 0, 0, 0.01, 0, 0"));
    auto plumb = loadCalibration(path("plumb.yaml"));
    auto fisheye = loadCalibration(path("fisheye.yml"));
    auto rational = loadCalibration(path("rational.yaml"));
    ASSERT_TRUE(plumb.ok() && fisheye.ok() && rational.ok());
    expectIntrinsics(*plumb);
    EXPECT_EQ(plumb->distortion.model, DistortionModel::RadialTangential);
    EXPECT_EQ(fisheye->distortion.model, DistortionModel::Fisheye);
    EXPECT_DOUBLE_EQ(fisheye->distortion.coeffs[3], -0.0005);
    EXPECT_EQ(rational->distortion.model, DistortionModel::Rational);
    EXPECT_DOUBLE_EQ(rational->distortion.coeffs[5], 0.01);
}

TEST_F(CalibrationTest, MissingAndMalformedFiles)
{
    EXPECT_EQ(loadCalibration(path("absent.yaml")).error().code, ErrorCode::NotFound);
    writeText("broken.yaml", "image_width: [640\ncamera_matrix: {\n");
    writeText("broken.xml", "<?xml version=\"1.0\"?>\n<opencv_storage><camera_matrix>");
    writeText("nomatrix.yaml", "image_width: 640\nimage_height: 480\n");
    writeText("badmatrix.yaml", "image_width: 640\nimage_height: 480\ncamera_matrix:\n  data: [1, 2, 3]\n");
    for (const char *name : {"broken.yaml", "broken.xml", "nomatrix.yaml", "badmatrix.yaml"}) {
        auto c = loadCalibration(path(name));
        ASSERT_FALSE(c.ok()) << name;
        EXPECT_EQ(c.error().code, ErrorCode::Malformed) << name;
        EXPECT_NE(c.error().message.find(name), std::string::npos) << c.error().message;
    }
}

TEST_F(CalibrationTest, ConfigImportsAndOverrides)
{
    writeOpenCv("cam.yaml", {-0.1, 0.02, 0.001, 0.002, -0.003});
    // The calibration's path is relative to the config's folder; fx and the coefficients are overridden.
    const DaemonConfig config = loadValid("[source]\nwidth = 1280\nheight = 960\n[camera]\ncalibration = "
                                          "\"cam.yaml\"\nrvec = [0, 0, 0]\ntvec = [0, 0, 0]\n[camera.pinhole]\n"
                                          "fx = 512\n[camera.distortion]\ncoefficients = [-0.2, 0.03]\n",
                                          dir_.string());
    EXPECT_EQ(config.camera.form, IntrinsicsForm::Pinhole);
    EXPECT_DOUBLE_EQ(config.camera.pinhole.fx, 512);
    EXPECT_DOUBLE_EQ(config.camera.pinhole.fy, 508.2);
    EXPECT_EQ(config.camera.distortion.model, DistortionModel::RadialTangential);
    EXPECT_DOUBLE_EQ(config.camera.distortion.coeffs[1], 0.03);
    EXPECT_DOUBLE_EQ(config.camera.distortion.coeffs[2], 0.0);
    // Built for a stream twice the calibration's size, against cv::projectPoints with K scaled by hand.
    // cv::projectPoints ignores K's skew, so it is added from the distorted y that OpenCV's v gives back.
    auto camera = config.camera.build(1280, 960);
    ASSERT_TRUE(camera.ok()) << camera.error().message;
    const double fy = 2 * 508.2, cy = 2 * 242.2 - 0.5, skew = 2 * 0.25;
    const cv::Matx33d k(1024, 0, 2 * 322.6 - 0.5, 0, fy, cy, 0, 0, 1);
    const std::vector<cv::Point3d> world{{0.2, -0.1, 1.5}};
    const auto expected = opencvProject(world, cv::Matx33d::eye(), {0, 0, 0}, k, {-0.2, 0.03, 0, 0, 0});
    const ProjectedPoint p = camera->project(glm::dvec3(0.2, -0.1, 1.5));
    EXPECT_NEAR(p.pixel.x, expected[0].x + skew * (expected[0].y - cy) / fy, 1e-6);
    EXPECT_NEAR(p.pixel.y, expected[0].y, 1e-6);
}

} // namespace
} // namespace overlayd::test
