// SPDX-License-Identifier: Apache-2.0
// `overlayd solve-pose` and `overlayd unproject` through the real binary, against OpenCV as the independent
// reference: pixels made by cv::projectPoints from the example's calibration (plumb_bob lens) and extrinsics must
// give those extrinsics back; unprojected pixels must meet the ground where the world points are.
#include <cmath>
#include <cstdio>
#include <random>
#include <sstream>

#include <opencv2/calib3d.hpp>

#include <gtest/gtest.h>

#include "harness.h"

namespace overlayd::test {
namespace {

// config/examples/distorted_pinhole.toml: calibration.yaml with fx overridden, and its rvec/tvec.
const cv::Matx33d kK(821.5, 0, 641.5, 0, 818.0, 358.5, 0, 0, 1);
const std::vector<double> kDistortion{-0.28, 0.09, 0.0008, -0.0005, -0.012};
const cv::Vec3d kRvec(2.0943951023931957, 0.0, 0.0), kTvec(0.0, 2.1650635094610964, 1.25);

std::string example()
{
    return std::string(OVERLAYD_SOURCE_DIR) + "/config/examples/distorted_pinhole.toml";
}

// Ground points and a few above it, all in view of the example camera (its 1280x720 image).
std::vector<cv::Point3d> worldPoints()
{
    return {{-1.5, 2.2, 0}, {0, 2.2, 0}, {1.5, 2.2, 0}, {-1, 3, 0}, {1, 3, 0}, {0, 5, 0}, {-0.5, 2, 0.5}, {0.7, 4, 1}};
}

std::vector<cv::Point2d> opencvPixels(const std::vector<cv::Point3d> &world)
{
    std::vector<cv::Point2d> pixels;
    cv::projectPoints(world, kRvec, kTvec, kK, kDistortion, pixels);
    return pixels;
}

std::string pointsFile(const std::vector<cv::Point3d> &world, const std::vector<cv::Point2d> &pixels)
{
    std::string text = "# x y z u v\n";
    char line[200];
    for (size_t i = 0; i < world.size(); ++i) {
        std::snprintf(line, sizeof(line), "%.17g, %.17g, %.17g, %.17g, %.17g\n", world[i].x, world[i].y, world[i].z,
                      pixels[i].x, pixels[i].y);
        text += line;
    }
    return text;
}

// The three numbers of "key = [a, b, c]" in solve-pose's output.
cv::Vec3d vectorAfter(const std::string &output, const std::string &key)
{
    const size_t at = output.find("\n" + key + " = [");
    cv::Vec3d v(NAN, NAN, NAN);
    if (at != std::string::npos)
        std::sscanf(output.c_str() + at + key.size() + 5, "%lf, %lf, %lf", &v[0], &v[1], &v[2]);
    return v;
}

// `overlayd project --json` of the points through a config (exact decimal arguments), and the pixels it printed
// (points without a pixel are left out).
std::vector<cv::Point2d> projectedPixels(const std::string &config, const std::vector<cv::Point3d> &points,
                                         const std::string &dir)
{
    const RunResult run = runOverlayd("project --config '" + config + "' --json --" + pointArguments(points), dir);
    EXPECT_EQ(run.exitStatus, 0) << run.all();
    std::vector<cv::Point2d> out;
    for (size_t at = run.out.find("\"pixel\":["); at != std::string::npos; at = run.out.find("\"pixel\":[", at + 1)) {
        double u = NAN, v = NAN;
        std::sscanf(run.out.c_str() + at + 9, "%lf,%lf", &u, &v);
        out.emplace_back(u, v);
    }
    return out;
}

double rmsOf(const std::string &output)
{
    const size_t at = output.find("RMS reprojection error ");
    return at == std::string::npos ? NAN : std::atof(output.c_str() + at + 23);
}

TEST(SolvePose, GivesBackTheExtrinsicsOpenCVProjectedThroughTheLens)
{
    const std::string dir = scratchDir("solve-pose-exact");
    const auto world = worldPoints();
    writeFile(dir + "/points.csv", pointsFile(world, opencvPixels(world)));
    const RunResult run = runOverlayd("solve-pose --config '" + example() + "' --points points.csv", dir);
    ASSERT_EQ(run.exitStatus, 0) << run.all();
    const cv::Vec3d rvec = vectorAfter(run.out, "rvec"), tvec = vectorAfter(run.out, "tvec");
    for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(rvec[k], kRvec[k], 1e-6) << run.out;
        EXPECT_NEAR(tvec[k], kTvec[k], 1e-6) << run.out;
    }
    EXPECT_LT(rmsOf(run.out), 1e-4) << run.out;
    EXPECT_EQ(run.out.find("warning"), std::string::npos) << run.out;
}

// --solver: the iterative solver on the 8 points and IPPE on 5 floor points give OpenCV's extrinsics back too; IPPE
// refuses points off a plane, the iterative solver fewer than 6 of them, and an unknown name is a usage error.
TEST(SolvePose, EverySolverGivesThePoseBackAndRefusesWhatItCannotTake)
{
    const std::string dir = scratchDir("solve-pose-solvers");
    const auto world = worldPoints();
    writeFile(dir + "/all.csv", pointsFile(world, opencvPixels(world)));
    const std::vector<cv::Point3d> floor{{-1.5, 1.5, 0}, {0, 1.5, 0}, {1.5, 1.5, 0}, {-1, 3, 0}, {1, 3, 0}, {0, 5, 0}};
    writeFile(dir + "/floor.csv", pointsFile(floor, opencvPixels(floor)));
    const std::vector<cv::Point3d> five(world.begin() + 3, world.end());
    writeFile(dir + "/five.csv", pointsFile(five, opencvPixels(five)));
    for (const char *solved : {"--solver iterative --points all.csv", "--solver ippe --points floor.csv",
                               "--solver iterative --points floor.csv"}) {
        const RunResult run = runOverlayd("solve-pose --config '" + example() + "' " + solved, dir);
        ASSERT_EQ(run.exitStatus, 0) << solved << "\n" << run.all();
        const cv::Vec3d rvec = vectorAfter(run.out, "rvec"), tvec = vectorAfter(run.out, "tvec");
        for (int k = 0; k < 3; ++k) {
            EXPECT_NEAR(rvec[k], kRvec[k], 1e-6) << solved << "\n" << run.out;
            EXPECT_NEAR(tvec[k], kTvec[k], 1e-6) << solved << "\n" << run.out;
        }
    }
    RunResult run = runOverlayd("solve-pose --config '" + example() + "' --solver ippe --points all.csv", dir);
    EXPECT_EQ(run.exitStatus, 1) << run.all();
    EXPECT_NE(run.err.find("the ippe solver takes coplanar points only"), std::string::npos) << run.err;
    run = runOverlayd("solve-pose --config '" + example() + "' --solver iterative --points five.csv", dir);
    EXPECT_EQ(run.exitStatus, 1) << run.all();
    EXPECT_NE(run.err.find("needs 6 or more points off a plane"), std::string::npos) << run.err;
    run = runOverlayd("solve-pose --config '" + example() + "' --solver ransac --points all.csv", dir);
    EXPECT_NE(run.exitStatus, 0);
    EXPECT_NE(run.err.find("ransac"), std::string::npos) << run.err;
}

// The alignment workflow end to end: a config whose pose is wrong and in another form (position + yaw/pitch/roll),
// solve-pose --write puts the solved pose into NAME.live.toml, and `project` through the config (with the drop-in
// merged) then puts the world points on OpenCV's pixels. The config file itself is left as it was.
TEST(SolvePose, WritesTheDropInThatProjectThenAgreesWith)
{
    const std::string dir = scratchDir("solve-pose-write");
    const std::vector<uint8_t> calibration =
        readFile(std::string(OVERLAYD_SOURCE_DIR) + "/config/examples/calibration.yaml");
    writeFile(dir + "/calibration.yaml", std::string(calibration.begin(), calibration.end()));
    const std::string config = "[source]\nkind = \"synthetic\"\nwidth = 1280\nheight = 720\n"
                               "[camera]\ncalibration = \"calibration.yaml\"\n"
                               "position = [0.0, -3.0, 2.0]\nyaw = 80.0\npitch = 20.0\n"
                               "near = 0.05\nfar = 100.0\n[camera.pinhole]\nfx = 821.5\n";
    writeFile(dir + "/cam.toml", config);
    const auto world = worldPoints();
    const auto pixels = opencvPixels(world);
    writeFile(dir + "/points.csv", pointsFile(world, pixels));
    const RunResult solve = runOverlayd("solve-pose --config cam.toml --points points.csv --write", dir);
    ASSERT_EQ(solve.exitStatus, 0) << solve.all();
    EXPECT_NE(solve.err.find("cam.live.toml"), std::string::npos) << solve.err;
    const std::vector<uint8_t> kept = readFile(dir + "/cam.toml");
    EXPECT_EQ(std::string(kept.begin(), kept.end()), config);

    const auto projected = projectedPixels(dir + "/cam.toml", world, dir);
    ASSERT_EQ(projected.size(), pixels.size());
    for (size_t i = 0; i < pixels.size(); ++i)
        EXPECT_LT(cv::norm(projected[i] - pixels[i]), 1e-5) << i;
}

// Each warning through the real binary, and only where it applies: five ground points (coplanar and few), one pixel
// 10 px off (a large RMS), and a ground set seen from 0.4 m up at 4-12 m (edge-on, about 3 degrees above it; pixels
// from `overlayd project` of a camera without distortion).
TEST(SolvePose, WarnsAboutFewCoplanarPointsALargeErrorAndAPlaneSeenEdgeOn)
{
    const std::string dir = scratchDir("solve-pose-warnings");
    const std::vector<cv::Point3d> ground{{-1.5, 1.5, 0}, {0, 1.5, 0}, {1.5, 1.5, 0}, {-1, 3, 0}, {1, 3, 0}};
    writeFile(dir + "/ground.csv", pointsFile(ground, opencvPixels(ground)));
    RunResult run = runOverlayd("solve-pose --config '" + example() + "' --points ground.csv", dir);
    ASSERT_EQ(run.exitStatus, 0) << run.all();
    EXPECT_NE(run.out.find("warning: the points are coplanar and few"), std::string::npos) << run.out;
    EXPECT_EQ(run.out.find("edge-on"), std::string::npos) << run.out;

    const auto world = worldPoints();
    auto pixels = opencvPixels(world);
    pixels[3].x += 10.0;
    writeFile(dir + "/off.csv", pointsFile(world, pixels));
    run = runOverlayd("solve-pose --config '" + example() + "' --points off.csv", dir);
    ASSERT_EQ(run.exitStatus, 0) << run.all();
    EXPECT_NE(run.out.find("warning: the RMS reprojection error is"), std::string::npos) << run.out;
    EXPECT_EQ(run.out.find("coplanar"), std::string::npos) << run.out;

    writeFile(dir + "/low.toml", "[source]\nkind = \"synthetic\"\nwidth = 640\nheight = 480\n"
                                 "[camera]\nposition = [0.0, 0.0, 0.4]\nyaw = 0.0\npitch = 2.0\nfov = 60.0\n");
    const std::vector<cv::Point3d> far{{4, -2, 0},  {4, 2, 0},  {8, -2.5, 0}, {8, 2.5, 0},
                                       {12, -3, 0}, {12, 3, 0}, {6, 0, 0}};
    const auto seen = projectedPixels(dir + "/low.toml", far, dir);
    ASSERT_EQ(seen.size(), far.size());
    writeFile(dir + "/far.csv", pointsFile(far, seen));
    run = runOverlayd("solve-pose --config low.toml --points far.csv", dir);
    ASSERT_EQ(run.exitStatus, 0) << run.all();
    EXPECT_NE(run.out.find("warning: the points' plane is seen nearly edge-on (2."), std::string::npos) << run.out;
}

// u and v swapped (a transposed image): the mirrored pose under the floor fits the ground marks; said so. A pixel
// outside the 1280x720 image is named, whichever side it leaves by; the points' own pixels raise neither warning.
TEST(SolvePose, WarnsAboutACameraBelowThePointsAndPixelsOutsideTheImage)
{
    const std::string dir = scratchDir("solve-pose-sanity");
    const std::vector<cv::Point3d> ground{{-1.5, 2.2, 0}, {0, 2.2, 0}, {1.5, 2.2, 0}, {-1, 3, 0},
                                          {1, 3, 0},      {0, 5, 0},   {-2, 6, 0},    {2, 4, 0}};
    auto pixels = opencvPixels(ground);
    writeFile(dir + "/ground.csv", pointsFile(ground, pixels));
    RunResult run = runOverlayd("solve-pose --config '" + example() + "' --points ground.csv", dir);
    ASSERT_EQ(run.exitStatus, 0) << run.all();
    EXPECT_EQ(run.out.find("below the plane"), std::string::npos) << run.out;
    EXPECT_EQ(run.out.find("outside the"), std::string::npos) << run.out;

    std::vector<cv::Point2d> swapped;
    for (const cv::Point2d &p : pixels)
        swapped.emplace_back(p.y, p.x);
    writeFile(dir + "/swapped.csv", pointsFile(ground, swapped));
    run = runOverlayd("solve-pose --config '" + example() + "' --points swapped.csv", dir);
    ASSERT_EQ(run.exitStatus, 0) << run.all();
    EXPECT_NE(run.out.find("# warning: the camera is below the plane of the points: are u and v swapped?"),
              std::string::npos)
        << run.out;
    EXPECT_LT(vectorAfter(run.out, "# position")[2], 0.0) << run.out;

    pixels[3] = {1300.25, 400};
    pixels[5] = {600, -3};
    writeFile(dir + "/outside.csv", pointsFile(ground, pixels));
    run = runOverlayd("solve-pose --config '" + example() + "' --points outside.csv", dir);
    ASSERT_EQ(run.exitStatus, 0) << run.all();
    EXPECT_NE(run.out.find("# warning: point 4's pixel (1300.25, 400) is outside the 1280x720 image"),
              std::string::npos)
        << run.out;
    EXPECT_NE(run.out.find("# warning: point 6's pixel (600, -3) is outside the 1280x720 image"), std::string::npos)
        << run.out;
    EXPECT_EQ(run.out.find("point 1's pixel"), std::string::npos) << run.out;
}

TEST(SolvePose, ReportsPixelNoiseInsteadOfHidingIt)
{
    const std::string dir = scratchDir("solve-pose-noise");
    const auto world = worldPoints();
    auto pixels = opencvPixels(world);
    std::mt19937 random(7);
    std::normal_distribution<double> noise(0.0, 0.5);
    for (cv::Point2d &p : pixels)
        p += cv::Point2d(noise(random), noise(random));
    writeFile(dir + "/points.csv", pointsFile(world, pixels));
    const RunResult run = runOverlayd("solve-pose --config '" + example() + "' --points points.csv", dir);
    ASSERT_EQ(run.exitStatus, 0) << run.all();
    const double rms = rmsOf(run.out);
    EXPECT_GT(rms, 0.1) << run.out;
    EXPECT_LT(rms, 1.0) << run.out;
    const cv::Vec3d tvec = vectorAfter(run.out, "tvec");
    EXPECT_LT(cv::norm(tvec - kTvec), 0.05) << run.out;
}

TEST(SolvePose, RefusesTooFewAndCollinearPointsAndNamesABadLine)
{
    const std::string dir = scratchDir("solve-pose-bad");
    const auto world = worldPoints();
    const auto pixels = opencvPixels(world);
    writeFile(dir + "/three.csv", pointsFile({world.begin(), world.begin() + 3}, {pixels.begin(), pixels.begin() + 3}));
    RunResult run = runOverlayd("solve-pose --config '" + example() + "' --points three.csv", dir);
    EXPECT_EQ(run.exitStatus, 1);
    EXPECT_NE(run.err.find("needs 4..10000 points, got 3"), std::string::npos) << run.all();

    const std::vector<cv::Point3d> line{{0, 1, 0}, {0, 2, 0}, {0, 3, 0}, {0, 4, 0}};
    writeFile(dir + "/line.csv", pointsFile(line, opencvPixels(line)));
    run = runOverlayd("solve-pose --config '" + example() + "' --points line.csv", dir);
    EXPECT_EQ(run.exitStatus, 1);
    EXPECT_NE(run.err.find("collinear"), std::string::npos) << run.all();

    writeFile(dir + "/bad.csv", "0 1 0 640 500\n0 2 0 640 nope\n");
    run = runOverlayd("solve-pose --config '" + example() + "' --points bad.csv", dir);
    EXPECT_EQ(run.exitStatus, 1);
    EXPECT_NE(run.err.find("bad.csv:2: 'nope' is not a finite number"), std::string::npos) << run.all();
    EXPECT_FALSE(run.crashed);
}

// A spreadsheet's CSV starts with a row of column names: solve-pose reads it as it reads the same points without,
// and `project --points` takes the same marks file (x y z used, u v ignored), putting the points on OpenCV's
// pixels. Only the first line may be names: one later is a bad line, named.
TEST(PointsFile, AHeaderRowIsReadAndProjectTakesTheMarksFile)
{
    const std::string dir = scratchDir("points-header");
    const auto world = worldPoints();
    const auto pixels = opencvPixels(world);
    std::string body = pointsFile(world, pixels);
    body = body.substr(body.find('\n') + 1); // without its comment line
    writeFile(dir + "/marks.csv", "x,y,z,u,v\n" + body);
    RunResult run = runOverlayd("solve-pose --config '" + example() + "' --points marks.csv", dir);
    ASSERT_EQ(run.exitStatus, 0) << run.all();
    const cv::Vec3d rvec = vectorAfter(run.out, "rvec"), tvec = vectorAfter(run.out, "tvec");
    for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(rvec[k], kRvec[k], 1e-6) << run.out;
        EXPECT_NEAR(tvec[k], kTvec[k], 1e-6) << run.out;
    }

    run = runOverlayd("project --config '" + example() + "' --json --points marks.csv", dir);
    ASSERT_EQ(run.exitStatus, 0) << run.all();
    size_t count = 0;
    for (size_t at = run.out.find("\"pixel\":["); at != std::string::npos; at = run.out.find("\"pixel\":[", at + 1)) {
        double u = NAN, v = NAN;
        std::sscanf(run.out.c_str() + at + 9, "%lf,%lf", &u, &v);
        ASSERT_LT(count, pixels.size()) << run.out;
        EXPECT_LT(cv::norm(cv::Point2d(u, v) - pixels[count]), 1e-6) << count << "\n" << run.out;
        ++count;
    }
    EXPECT_EQ(count, world.size()) << run.out;

    // "# comment", then the header with blanks and quotes as some programs write them, then x y z lines.
    writeFile(dir + "/route.txt", "# planned route\n\"X\" \"Y\" \"Z\"\n0 1.5 0\n+1 3 0\n");
    run = runOverlayd("project --config '" + example() + "' --points route.txt", dir);
    EXPECT_EQ(run.exitStatus, 0) << run.all();

    writeFile(dir + "/twice.csv", "x,y,z,u,v\n" + body + "x,y,z,u,v\n");
    run = runOverlayd("solve-pose --config '" + example() + "' --points twice.csv", dir);
    EXPECT_EQ(run.exitStatus, 1) << run.all();
    EXPECT_NE(run.err.find("twice.csv:" + std::to_string(world.size() + 2) + ": 'x' is not a finite number"),
              std::string::npos)
        << run.all();
    writeFile(dir + "/four.csv", "x,y,z,u\n0,1.5,0,640\n");
    run = runOverlayd("project --config '" + example() + "' --points four.csv", dir);
    EXPECT_EQ(run.exitStatus, 1) << run.all();
    EXPECT_NE(run.err.find("four.csv:2: expected x y z or x y z u v, got 4 numbers"), std::string::npos) << run.all();
    // A first line with a number in it is data, not a header: named as a bad line.
    writeFile(dir + "/mixed.csv", "x,1,z,u,v\n" + body);
    run = runOverlayd("solve-pose --config '" + example() + "' --points mixed.csv", dir);
    EXPECT_EQ(run.exitStatus, 1) << run.all();
    EXPECT_NE(run.err.find("mixed.csv:1: 'x' is not a finite number"), std::string::npos) << run.all();
}

TEST(Unproject, PixelsOpenCVProjectedMeetTheGroundWhereTheirPointsAre)
{
    const std::string dir = scratchDir("unproject-ground");
    std::vector<cv::Point3d> ground;
    for (const cv::Point3d &p : worldPoints())
        if (p.z == 0.0)
            ground.push_back(p);
    const auto pixels = opencvPixels(ground);
    std::string args = "unproject --json --config '" + example() + "' --";
    for (const cv::Point2d &p : pixels)
        args += " " + std::to_string(p.x) + " " + std::to_string(p.y);
    const RunResult run = runOverlayd(args, dir);
    ASSERT_EQ(run.exitStatus, 0) << run.all();
    // One object per pixel: {"pixel":[..],"origin":[..],"direction":[..],"hit":[x,y,z],"reason":null}
    size_t at = 0;
    for (const cv::Point3d &expected : ground) {
        at = run.out.find("\"hit\":[", at);
        ASSERT_NE(at, std::string::npos) << run.out;
        cv::Vec3d hit;
        std::sscanf(run.out.c_str() + at + 7, "%lf,%lf,%lf", &hit[0], &hit[1], &hit[2]);
        // std::to_string keeps 6 decimals of the pixel: about 1e-6 px, well under a millimetre on the ground.
        EXPECT_NEAR(hit[0], expected.x, 1e-4) << run.out;
        EXPECT_NEAR(hit[1], expected.y, 1e-4) << run.out;
        EXPECT_NEAR(hit[2], 0.0, 1e-9) << run.out;
        ++at;
    }
}

// The round trip through the real binary: project ground points through the distorting lens, unproject their pixels
// onto the ground, project those again: the same points (1e-6 m) and the same pixels (1e-6 px).
TEST(Unproject, ProjectUnprojectProjectComesBack)
{
    const std::string dir = scratchDir("round-trip");
    const std::vector<cv::Point3d> world{{-1.5, 1.5, 0}, {1.5, 1.5, 0}, {-1, 3, 0}, {1, 3, 0}, {0, 5, 0}, {2, 4, 0}};
    const auto pixels = projectedPixels(example(), world, dir);
    ASSERT_EQ(pixels.size(), world.size());
    std::string args = "unproject --config '" + example() + "' --json --";
    char number[64];
    for (const cv::Point2d &p : pixels) {
        std::snprintf(number, sizeof number, " %.17g %.17g", p.x, p.y);
        args += number;
    }
    const RunResult unprojected = runOverlayd(args, dir);
    ASSERT_EQ(unprojected.exitStatus, 0) << unprojected.all();
    std::vector<cv::Point3d> ground;
    for (size_t at = unprojected.out.find("\"hit\":["); at != std::string::npos;
         at = unprojected.out.find("\"hit\":[", at + 1)) {
        double x = NAN, y = NAN, z = NAN;
        std::sscanf(unprojected.out.c_str() + at + 7, "%lf,%lf,%lf", &x, &y, &z);
        ground.emplace_back(x, y, z);
    }
    ASSERT_EQ(ground.size(), world.size()) << unprojected.out;
    for (size_t i = 0; i < world.size(); ++i)
        EXPECT_LT(cv::norm(ground[i] - world[i]), 1e-6) << i << ": " << unprojected.out;
    const auto again = projectedPixels(example(), ground, dir);
    ASSERT_EQ(again.size(), pixels.size());
    for (size_t i = 0; i < pixels.size(); ++i)
        EXPECT_LT(cv::norm(again[i] - pixels[i]), 1e-6) << i;
}

TEST(Unproject, ARayThatMissesThePlaneSaysWhy)
{
    const std::string dir = scratchDir("unproject-miss");
    // The ceiling z = 3, above the camera (2.5 m up, looking down): behind every ray of the image.
    const RunResult run = runOverlayd("unproject --config '" + example() + "' --plane \"0 0 1 -3\" -- 640 5", dir);
    ASSERT_EQ(run.exitStatus, 0) << run.all();
    EXPECT_NE(run.out.find("misses the plane: the plane is behind the camera"), std::string::npos) << run.out;
    // Another plane: the wall y = 6 (normal -y, d = 6) is met by the same pixel.
    const RunResult wall = runOverlayd("unproject --config '" + example() + "' --plane \"0 -1 0 6\" -- 640 5", dir);
    ASSERT_EQ(wall.exitStatus, 0) << wall.all();
    EXPECT_NE(wall.out.find("meets the plane at ("), std::string::npos) << wall.out;
    EXPECT_NE(wall.out.find(", 6.000000, "), std::string::npos) << wall.out;
}

} // namespace
} // namespace overlayd::test
