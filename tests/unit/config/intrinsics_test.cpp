// SPDX-License-Identifier: Apache-2.0
// Every intrinsics form, near/far, depth range, distortion and viewport of [camera]/[viewport], against pixels
// computed by hand from the forms' definitions or by cv::projectPoints / cv::fisheye::projectPoints.
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <string>

#include <gtest/gtest.h>

#include "config_test_util.h"

namespace overlayd::test {
namespace {

// The camera's optical frame is the world's (x right, y down, z forward), so hand computations use X/Z, Y/Z.
const std::string kHeader = "[source]\nwidth = 1280\nheight = 720\n";
const std::string kIdentityPose = "[camera]\nrvec = [0, 0, 0]\ntvec = [0, 0, 0]\n";

Camera buildCamera(const std::string &toml)
{
    const DaemonConfig config = loadValid(toml);
    auto camera = config.camera.build(1280, 720);
    EXPECT_TRUE(camera.ok()) << (camera ? "" : camera.error().message);
    return camera.value();
}

void expectPixel(const Camera &camera, const glm::dvec3 &world, double u, double v, double tolerance = 1e-9)
{
    const ProjectedPoint p = camera.project(world);
    ASSERT_NE(p.status, PointStatus::Clipped);
    // (u, v) are in the viewport's origin, as a user reads them; the camera answers in memory order.
    const glm::dvec2 pixel = camera.viewport().toUser(p.pixel);
    EXPECT_NEAR(pixel.x, u, tolerance);
    EXPECT_NEAR(pixel.y, v, tolerance);
}

TEST(Intrinsics, VerticalFieldOfView)
{
    const Camera camera = buildCamera(kHeader + kIdentityPose + "fov = 60\nfov_axis = \"vertical\"\n");
    const double f = 360.0 / std::tan(M_PI / 6); // half the height over tan(half the vertical fov)
    expectPixel(camera, {1, -0.5, 4}, 639.5 + f * 0.25, 359.5 - f * 0.125);
}

TEST(Intrinsics, HorizontalFieldOfView)
{
    const Camera camera = buildCamera(kHeader + kIdentityPose + "fov = 90\nfov_axis = \"horizontal\"\n");
    expectPixel(camera, {1, 0.5, 4}, 639.5 + 640 * 0.25, 359.5 + 640 * 0.125);
}

TEST(Intrinsics, DefaultFieldOfViewHonoursItsAxis)
{
    // No fov: 60 degrees, here across the width.
    const Camera camera = buildCamera(kHeader + kIdentityPose + "fov_axis = \"horizontal\"\n");
    const double f = 640.0 / std::tan(M_PI / 6);
    expectPixel(camera, {1, 0.5, 4}, 639.5 + f * 0.25, 359.5 + f * 0.125);
}

TEST(Intrinsics, OffAxisFrustum)
{
    const Camera camera = buildCamera(kHeader + kIdentityPose +
                                      "near = 0.1\nfar = 50\n[camera.frustum]\nleft = -0.2\nright = 0.1\n"
                                      "bottom = -0.05\ntop = 0.1\n");
    // glFrustum: x_ndc = (2 n x/(-z) - (r + l)) / (r - l) in the internal frame (x = X, y = -Y, -z = Z).
    const double X = 0.3, Y = -0.2, Z = 2.0;
    const double xNdc = (2 * 0.1 * X / Z + 0.1) / 0.3, yNdc = (2 * 0.1 * -Y / Z - 0.05) / 0.15;
    expectPixel(camera, {X, Y, Z}, (xNdc + 1) * 640 - 0.5, (1 - yNdc) * 360 - 0.5);
}

TEST(Intrinsics, PinholeForAnotherImageSizeIsScaled)
{
    const Camera camera = buildCamera(kHeader + kIdentityPose +
                                      "[camera.pinhole]\nfx = 400\nfy = 410\ncx = 300\ncy = 200\n"
                                      "width = 640\nheight = 360\n");
    // Twice the size: f doubles, and pixel centres map as u' = 2 (u + 0.5) - 0.5.
    const cv::Matx33d k(800, 0, 600.5, 0, 820, 400.5, 0, 0, 1);
    const std::vector<cv::Point3d> world{{0.5, -0.25, 3}, {-1, 0.4, 2}};
    const auto expected = opencvProject(world, cv::Matx33d::eye(), {0, 0, 0}, k, {});
    for (size_t i = 0; i < world.size(); ++i)
        expectPixel(camera, {world[i].x, world[i].y, world[i].z}, expected[i].x, expected[i].y);
    ASSERT_TRUE(camera.projection().pinholeIntrinsics().has_value());
    EXPECT_DOUBLE_EQ(camera.projection().pinholeIntrinsics()->cx, 600.5);
}

// A 4:3 calibration (1600x1200) on a 16:9 stream (1280x720) is not a scaling: refused at the key, naming both sizes
// and the way out, by check-config as by the camera build.
TEST(Intrinsics, PinholeOfAnotherAspectIsRefusedWithoutACrop)
{
    const auto problems = loadInvalid(kHeader + kIdentityPose +
                                      "[camera.pinhole]\nfx = 1000\nfy = 1000\ncx = 799.5\ncy = 599.5\n"
                                      "width = 1600\nheight = 1200\n");
    EXPECT_TRUE(hasProblem(problems, "camera.pinhole", "1600x1200 (4:3) image but the stream is 1280x720 (16:9)"))
        << formatProblems(problems);
    EXPECT_TRUE(hasProblem(problems, "camera.pinhole", "calibration_crop = \"center\"")) << formatProblems(problems);
}

// The calibrated size is both numbers or neither: one alone would be read as "not given" and silently ignored.
TEST(Intrinsics, PinholeWidthWithoutHeightIsRefusedAtItsKey)
{
    const std::string pinhole = "[camera.pinhole]\nfx = 1000\nfy = 1000\ncx = 639.5\ncy = 359.5\n";
    for (const auto &[keys, refusedKey] :
         {std::pair{"width = 1280\n", "camera.pinhole.width"}, std::pair{"height = 720\n", "camera.pinhole.height"}}) {
        const auto problems = loadInvalid(kHeader + kIdentityPose + pinhole + keys);
        EXPECT_TRUE(hasProblem(problems, refusedKey, "width and height go together")) << formatProblems(problems);
    }
}

// calibration_crop = "center": the stream is the largest centred 16:9 region of the 4:3 calibration (1600x900 from
// row 150), scaled by 0.8. Worked by hand: the calibrated centre (799.5, 599.5) is the stream's (639.5, 359.5);
// 50 px below it (cy 649.5) is 40 px below (399.5); f 1000 -> 800. The stream's pixels against cv::projectPoints
// with that K.
TEST(Intrinsics, PinholeOfAnotherAspectWithACentreCropIsCroppedAndScaled)
{
    const Camera camera = buildCamera(kHeader + "[camera]\nrvec = [0, 0, 0]\ntvec = [0, 0, 0]\n"
                                                "calibration_crop = \"center\"\n"
                                                "[camera.pinhole]\nfx = 1000\nfy = 1000\ncx = 799.5\ncy = 649.5\n"
                                                "width = 1600\nheight = 1200\n");
    ASSERT_TRUE(camera.projection().pinholeIntrinsics().has_value());
    const PinholeIntrinsics k = *camera.projection().pinholeIntrinsics();
    EXPECT_DOUBLE_EQ(k.fx, 800.0);
    EXPECT_DOUBLE_EQ(k.fy, 800.0);
    EXPECT_DOUBLE_EQ(k.cx, 639.5);
    EXPECT_DOUBLE_EQ(k.cy, 399.5);
    const std::vector<cv::Point3d> world{{0.5, -0.25, 3}, {-1, 0.4, 2}};
    const auto expected =
        opencvProject(world, cv::Matx33d::eye(), {0, 0, 0}, cv::Matx33d(800, 0, 639.5, 0, 800, 399.5, 0, 0, 1), {});
    for (size_t i = 0; i < world.size(); ++i)
        expectPixel(camera, {world[i].x, world[i].y, world[i].z}, expected[i].x, expected[i].y);

    // The other way round: a 16:9 calibration (1920x1080) on a 4:3 stream (640x480) is its centred 1440x1080
    // region from column 240, scaled by 4/9: the centre (959.5, 539.5) lands on (319.5, 239.5).
    DaemonConfig config = loadValid(kHeader + "[camera]\nrvec = [0, 0, 0]\ntvec = [0, 0, 0]\n"
                                              "calibration_crop = \"center\"\n"
                                              "[camera.pinhole]\nfx = 900\nfy = 900\ncx = 959.5\ncy = 539.5\n"
                                              "width = 1920\nheight = 1080\n");
    auto small = config.camera.build(640, 480);
    ASSERT_TRUE(small.ok()) << small.error().message;
    EXPECT_NEAR(small->projection().pinholeIntrinsics()->cx, 319.5, 1e-12);
    EXPECT_NEAR(small->projection().pinholeIntrinsics()->cy, 239.5, 1e-12);
    EXPECT_NEAR(small->projection().pinholeIntrinsics()->fx, 400.0, 1e-12);
    const std::string note = config.camera.calibrationScaling(small->viewport());
    EXPECT_NE(note.find("calibrated at 1920x1080 (16:9) cropped to the centre and scaled to the 640x480 (4:3)"),
              std::string::npos)
        << note;
}

// Within a pixel of the same aspect (1920x1080 -> 1280x720 exactly, 640x360 -> 1280x721 by rounding) is a scaling.
TEST(Intrinsics, PinholeOfTheSameAspectIsScaledAndSaysSo)
{
    DaemonConfig config = loadValid(kHeader + kIdentityPose +
                                    "[camera.pinhole]\nfx = 900\nfy = 900\ncx = 959.5\ncy = 539.5\n"
                                    "width = 1920\nheight = 1080\n");
    auto camera = config.camera.build(1280, 720);
    ASSERT_TRUE(camera.ok()) << camera.error().message;
    EXPECT_NEAR(camera->projection().pinholeIntrinsics()->fx, 600.0, 1e-12);
    EXPECT_NE(config.camera.calibrationScaling(camera->viewport()).find("scaled to the 1280x720"), std::string::npos);
    EXPECT_TRUE(config.camera.build(1281, 721).ok());
    EXPECT_FALSE(config.camera.build(1280, 740).ok());
    auto same = config.camera.build(1920, 1080);
    ASSERT_TRUE(same.ok());
    EXPECT_EQ(config.camera.calibrationScaling(same->viewport()), "");
}

TEST(Intrinsics, ViewingPipelineWindowModel)
{
    const Camera camera = buildCamera(kHeader + kIdentityPose +
                                      "near = 0.5\nfar = 100\n[camera.window]\nfocal = 2\ncentre = [0.2, 0.1]\n"
                                      "half_width = 1\nhalf_height = 0.5\n");
    // The window at distance `focal`, centred at (0.2, 0.1) in the internal frame, spans NDC [-1, 1].
    const double X = 0.4, Y = -0.3, Z = 2.5;
    const double xNdc = (X / Z * 2 - 0.2) / 1.0, yNdc = (-Y / Z * 2 - 0.1) / 0.5;
    expectPixel(camera, {X, Y, Z}, (xNdc + 1) * 640 - 0.5, (1 - yNdc) * 360 - 0.5);
}

const std::string kTopDown = "[camera]\neye = [0, 0, 50]\ntarget = [0, 0, 0]\nup = [0, 1, 0]\nnear = 1\nfar = 100\n";

TEST(Intrinsics, OrthographicBox)
{
    const Camera camera =
        buildCamera(kHeader + kTopDown + "[camera.orthographic]\nleft = -10\nright = 10\nbottom = -5\ntop = 5\n");
    expectPixel(camera, {3, 2, 0}, (3 + 10) / 20.0 * 1280 - 0.5, (5 - 2) / 10.0 * 720 - 0.5);
    expectPixel(camera, {3, 2, 30}, (3 + 10) / 20.0 * 1280 - 0.5, (5 - 2) / 10.0 * 720 - 0.5);
}

TEST(Intrinsics, WindowOrthographic)
{
    const Camera camera = buildCamera(kHeader + kTopDown + "[camera.orthographic]\nwidth = 20\nheight = 10\n");
    expectPixel(camera, {-4, -1, 0}, (-4 + 10) / 20.0 * 1280 - 0.5, (5 + 1) / 10.0 * 720 - 0.5);
}

TEST(Intrinsics, DepthRangeAndFarPlane)
{
    const std::string base = kHeader + kIdentityPose + "fov = 60\nnear = 0.5\n";
    const Camera zeroToOne = buildCamera(base + "far = 10\ndepth_range = \"0..1\"\n");
    EXPECT_NEAR(zeroToOne.project(glm::dvec3(0, 0, 0.5)).depth, 0.0, 1e-12);
    EXPECT_NEAR(zeroToOne.project(glm::dvec3(0, 0, 10)).depth, 1.0, 1e-12);
    EXPECT_EQ(zeroToOne.project(glm::dvec3(0, 0, 11)).status, PointStatus::Clipped);
    const Camera minusOne = buildCamera(base + "far = 10\ndepth_range = \"-1..1\"\n");
    EXPECT_NEAR(minusOne.project(glm::dvec3(0, 0, 0.5)).depth, -1.0, 1e-12);
    const Camera infinite = buildCamera(base + "far = \"inf\"\n");
    EXPECT_FALSE(infinite.projection().hasFarPlane());
    EXPECT_EQ(infinite.project(glm::dvec3(0, 0, 1e9)).status, PointStatus::Visible);

    // An orthographic box has no infinite far side: the refusal is at far, and says so (not "bounds not finite").
    const auto problems = loadInvalid(kHeader + kIdentityPose +
                                      "far = \"inf\"\n[camera.orthographic]\nleft = -2\nright = 2\nbottom = -1\n"
                                      "top = 1\n");
    ASSERT_EQ(problems.size(), 1u) << formatProblems(problems);
    EXPECT_TRUE(hasProblem(problems, "camera.far", "orthographic camera needs a finite far plane"))
        << formatProblems(problems);
}

TEST(Intrinsics, PlumbBobDistortionMatchesOpenCv)
{
    const Camera camera = buildCamera(kHeader + kIdentityPose +
                                      "[camera.pinhole]\nfx = 700\nfy = 690\ncx = 630\ncy = 350\n"
                                      "[camera.distortion]\nmodel = \"plumb_bob\"\n"
                                      "coefficients = [-0.2, 0.05, 0.001, -0.002, 0.01]\n");
    const cv::Matx33d k(700, 0, 630, 0, 690, 350, 0, 0, 1);
    const std::vector<cv::Point3d> world{{0.3, -0.2, 2}, {-0.5, 0.25, 1.5}, {0, 0, 1}};
    const auto expected = opencvProject(world, cv::Matx33d::eye(), {0, 0, 0}, k, {-0.2, 0.05, 0.001, -0.002, 0.01});
    for (size_t i = 0; i < world.size(); ++i)
        expectPixel(camera, {world[i].x, world[i].y, world[i].z}, expected[i].x, expected[i].y, 1e-6);
}

TEST(Intrinsics, EquidistantDistortionMatchesOpenCvFisheye)
{
    const Camera camera = buildCamera(kHeader + kIdentityPose +
                                      "[camera.pinhole]\nfx = 500\nfy = 500\ncx = 639.5\ncy = 359.5\n"
                                      "[camera.distortion]\nmodel = \"equidistant\"\n"
                                      "coefficients = [0.05, -0.01, 0.002, -0.0005]\n");
    const std::vector<cv::Point3d> world{{0.8, -0.4, 1.5}, {-0.3, 0.6, 1}};
    std::vector<cv::Point2d> expected;
    cv::fisheye::projectPoints(world, expected, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0),
                               cv::Matx33d(500, 0, 639.5, 0, 500, 359.5, 0, 0, 1),
                               cv::Vec4d(0.05, -0.01, 0.002, -0.0005));
    for (size_t i = 0; i < world.size(); ++i)
        expectPixel(camera, {world[i].x, world[i].y, world[i].z}, expected[i].x, expected[i].y, 1e-6);
}

// max_field_deg is the full field in degrees, in (0, 360), of an equidistant lens only; declared beyond 180 the
// camera sees behind its plane, otherwise (and by default) it does not.
TEST(Intrinsics, FisheyeFieldOfViewIsDeclaredAndChecked)
{
    const std::string lens = kHeader + kIdentityPose +
                             "[camera.pinhole]\nfx = 330\nfy = 330\ncx = 639.5\ncy = 359.5\n"
                             "[camera.distortion]\nmodel = \"equidistant\"\n"
                             "coefficients = [-0.013, -0.0037, 0.0016, -0.0004]\n";
    EXPECT_FALSE(buildCamera(lens).seesBehind());
    EXPECT_FALSE(buildCamera(lens + "max_field_deg = 180\n").seesBehind());
    EXPECT_TRUE(buildCamera(lens + "max_field_deg = 220\n").seesBehind());
    for (const char *bad : {"0", "-10", "360", "400", "nan", "\"wide\""}) {
        const auto problems = loadInvalid(lens + "max_field_deg = " + bad + "\n");
        EXPECT_TRUE(hasProblem(problems, "camera.distortion.max_field_deg", "")) << bad << formatProblems(problems);
    }
    const auto plumbBob = loadInvalid(kHeader + kIdentityPose +
                                      "[camera.distortion]\nmodel = \"plumb_bob\"\n"
                                      "coefficients = [0.1, 0, 0, 0, 0]\nmax_field_deg = 220\n");
    EXPECT_TRUE(hasProblem(plumbBob, "camera.distortion.max_field_deg", "only an equidistant (fisheye) lens"))
        << formatProblems(plumbBob);
}

TEST(Viewport, BottomLeftOriginFlipsRows)
{
    const std::string camera = kIdentityPose + "fov = 90\nfov_axis = \"horizontal\"\n";
    const Camera top = buildCamera(kHeader + camera);
    const Camera bottom = buildCamera(kHeader + camera + "[viewport]\norigin = \"bottom-left\"\n");
    const glm::dvec3 world(0.4, 0.3, 2);
    // Hand: u = 639.5 + 640 * 0.2, v (top-left) = 359.5 + 640 * 0.15; bottom-left counts rows from the bottom.
    expectPixel(top, world, 767.5, 455.5);
    expectPixel(bottom, world, 767.5, 719 - 455.5);
}

TEST(Viewport, WindowScissorAndPinholeWithoutImageSize)
{
    // A pinhole without width/height refers to the viewport window, which starts at (100, 50).
    const Camera camera = buildCamera(kHeader + kIdentityPose +
                                      "[camera.pinhole]\nfx = 300\nfy = 300\ncx = 319.5\ncy = 179.5\n"
                                      "[viewport]\nwindow = [100, 50, 640, 360]\nscissor = [100, 50, 320, 360]\n");
    expectPixel(camera, {0.5, 0.2, 2}, 100 + 319.5 + 75, 50 + 179.5 + 30);
    EXPECT_EQ(camera.viewport().scissor(), (PixelRect{100, 50, 320, 360}));
    EXPECT_EQ(camera.project(glm::dvec3(0.5, 0.2, 2)).status, PointStatus::Outside);
}

} // namespace
} // namespace overlayd::test

namespace overlayd::test {
namespace {

// calibration_crop = [x, y, width, height]: the stream is that region of the calibrated image scaled to the stream.
// Worked by hand for a 4:3 1600x1200 calibration (f 1000, centre (799.5, 649.5)) and a 1280x720 stream made from the
// region [100, 300, 1200, 675] (off-centre, 16:9): s = 1280 / 1200 = 720 / 675 = 16/15, f' = 1000 s = 1066.67,
// cx' = (799.5 + 0.5 - 100) s - 0.5 = 746.1667, cy' = (649.5 + 0.5 - 300) s - 0.5 = 372.8333 (pixel centres at
// integers, as every scaling here); pixels against cv::projectPoints with that K.
TEST(Intrinsics, PinholeWithAnExplicitCropRegionIsCroppedThereAndScaled)
{
    const Camera camera = buildCamera(kHeader + "[camera]\nrvec = [0, 0, 0]\ntvec = [0, 0, 0]\n"
                                                "calibration_crop = [100, 300, 1200, 675]\n"
                                                "[camera.pinhole]\nfx = 1000\nfy = 1000\ncx = 799.5\ncy = 649.5\n"
                                                "width = 1600\nheight = 1200\n");
    ASSERT_TRUE(camera.projection().pinholeIntrinsics().has_value());
    const PinholeIntrinsics k = *camera.projection().pinholeIntrinsics();
    const double s = 16.0 / 15.0;
    EXPECT_NEAR(k.fx, 1000.0 * s, 1e-9);
    EXPECT_NEAR(k.fy, 1000.0 * s, 1e-9);
    EXPECT_NEAR(k.cx, 700.0 * s - 0.5, 1e-9);
    EXPECT_NEAR(k.cy, 350.0 * s - 0.5, 1e-9);
    const cv::Matx33d expectedK(1000.0 * s, 0, 700.0 * s - 0.5, 0, 1000.0 * s, 350.0 * s - 0.5, 0, 0, 1);
    const std::vector<cv::Point3d> world{{0.5, -0.25, 3}, {-1, 0.4, 2}, {0.02, 0.01, 5}};
    const auto expected = opencvProject(world, cv::Matx33d::eye(), {0, 0, 0}, expectedK, {});
    for (size_t i = 0; i < world.size(); ++i)
        expectPixel(camera, {world[i].x, world[i].y, world[i].z}, expected[i].x, expected[i].y);
}

// 2x2 binning: the whole 2560x1440 sensor as calibrated, streamed at 1280x720, is crop = the whole sensor, scale 0.5;
// and the same size as calibrated with a smaller region is a digital zoom (scale 2 from [320, 180, 640, 360]).
TEST(Intrinsics, AnExplicitCropDescribesBinningAndZoom)
{
    DaemonConfig binned = loadValid(kHeader + kIdentityPose +
                                    "calibration_crop = [0, 0, 2560, 1440]\n"
                                    "[camera.pinhole]\nfx = 2000\nfy = 2000\n"
                                    "cx = 1279.5\ncy = 719.5\nwidth = 2560\nheight = 1440\n");
    auto camera = binned.camera.build(1280, 720);
    ASSERT_TRUE(camera.ok()) << camera.error().message;
    EXPECT_NEAR(camera->projection().pinholeIntrinsics()->fx, 1000.0, 1e-12);
    EXPECT_NEAR(camera->projection().pinholeIntrinsics()->cx, 639.5, 1e-12);
    EXPECT_NEAR(camera->projection().pinholeIntrinsics()->cy, 359.5, 1e-12);
    EXPECT_NE(binned.camera.calibrationScaling(camera->viewport()).find("cropped to calibration_crop"),
              std::string::npos);

    DaemonConfig zoomed = loadValid(kHeader + kIdentityPose +
                                    "calibration_crop = [320, 180, 640, 360]\n"
                                    "[camera.pinhole]\nfx = 500\nfy = 500\n"
                                    "cx = 639.5\ncy = 359.5\nwidth = 1280\nheight = 720\n");
    auto zoom = zoomed.camera.build(1280, 720);
    ASSERT_TRUE(zoom.ok()) << zoom.error().message;
    EXPECT_NEAR(zoom->projection().pinholeIntrinsics()->fx, 1000.0, 1e-12);
    EXPECT_NEAR(zoom->projection().pinholeIntrinsics()->cx, (639.5 + 0.5 - 320) * 2 - 0.5, 1e-12);
    EXPECT_NEAR(zoom->projection().pinholeIntrinsics()->cy, (359.5 + 0.5 - 180) * 2 - 0.5, 1e-12);
}

// Refused at camera.calibration_crop with its line: outside the calibrated image, empty, another aspect than the
// stream's by more than a pixel, not four numbers. Under 1 px of aspect is allowed (1201x676 -> 1280x720.47).
TEST(Intrinsics, AnExplicitCropOutsideTheImageEmptyOrOfAnotherAspectIsRefused)
{
    const std::string pinhole = "[camera.pinhole]\nfx = 1000\nfy = 1000\ncx = 799.5\ncy = 599.5\n"
                                "width = 1600\nheight = 1200\n";
    const struct {
        const char *crop, *words;
    } cases[] = {
        {"[500, 600, 1200, 675]", "reaches outside the calibrated 1600x1200 (4:3) image"},
        {"[-1, 0, 1200, 675]", "x and y must be >= 0, width and height > 0"},
        {"[0, 0, 0, 675]", "x and y must be >= 0, width and height > 0"},
        {"[0, 0, 1200, 700]", "is not of the stream's aspect (1280x720 (16:9))"},
        {"[0, 0, 1600, 1200]", "is not of the stream's aspect"},
        {"[0, 0, 1200]", "got 3 numbers"},
        {"\"left\"", "unknown value 'left'"},
    };
    for (const auto &c : cases) {
        const auto problems = loadInvalid(kHeader + kIdentityPose + "calibration_crop = " + c.crop + "\n" + pinhole);
        EXPECT_TRUE(hasProblem(problems, "camera.calibration_crop", c.words)) << c.crop << "\n"
                                                                              << formatProblems(problems);
        bool located = false;
        for (const ConfigProblem &p : problems)
            located = located || (p.key == "camera.calibration_crop" && p.line == 7);
        EXPECT_TRUE(located) << c.crop << "\n" << formatProblems(problems);
    }
    loadValid(kHeader + kIdentityPose + "calibration_crop = [0, 0, 1201, 676]\n" + pinhole);
}

// Numbers as written: a float is rounded to double once. The value is 1 + 2^-53 (halfway between 1 and the next
// double 1 + 2^-52) plus 1e-60: correctly rounded it is 1 + 2^-52, but rounded first to long double (x86's 64-bit
// mantissa, or arm64's 113-bit one, both hold 1 + 2^-53 exactly and lose the 1e-60) and then to double it ties to
// even, 1. toml++ (built without float charconv, so std::istringstream >> double, which is strtod) rounds once.
TEST(Intrinsics, FloatsAreRoundedToDoubleOnce)
{
    const std::string written = "1.000000000000000111022302462515654042363166809082031250000001";
    double once = 0.0;
    std::from_chars(written.data(), written.data() + written.size(), once);
    const double twice = static_cast<double>(std::strtold(written.c_str(), nullptr));
    ASSERT_EQ(once, std::nextafter(1.0, 2.0));
    ASSERT_NE(once, twice) << "the value must tell one rounding from two";
    const DaemonConfig config = loadValid(kHeader + kIdentityPose + "near = " + written + "\n");
    EXPECT_EQ(config.camera.near, once);
}

} // namespace
} // namespace overlayd::test
