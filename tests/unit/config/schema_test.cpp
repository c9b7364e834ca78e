// SPDX-License-Identifier: Apache-2.0
// The schema: the pinned [daemon]/[source]/[[sink]] keys, frames, every annotation type and style form, defaults,
// path resolution, pose/intrinsics form conflicts, and the "did you mean" machinery.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "config/problems.h"
#include "config_test_util.h"

namespace overlayd::test {
namespace {

TEST(Schema, EmptyFileGivesTheDefaults)
{
    const DaemonConfig config = loadValid("");
    EXPECT_EQ(config.source.kind, SourceKind::Synthetic);
    EXPECT_EQ(config.source.width, 1280u);
    EXPECT_EQ(config.daemon.logLevel, LogLevel::Info);
    EXPECT_TRUE(config.sinks.empty());
    EXPECT_EQ(config.camera.form, IntrinsicsForm::FieldOfView);
}

TEST(Schema, PinnedDaemonSourceAndSinkKeys)
{
    // The replay's file must exist (check-config refuses a missing one): a config folder holding it.
    const std::string base = ::testing::TempDir() + "schema-pinned";
    std::filesystem::create_directories(base + "/clips");
    std::ofstream(base + "/clips/in.y4m") << "raw bytes";
    const DaemonConfig config = loadValid(R"(
[daemon]
log_level = "warning"
stats_interval = 2.5
[source]
kind = "replay"
format = "NV12"
width = 640
height = 480
fps = 12.5
colorimetry = "bt709-full"
[source.synthetic]
pattern = "noise"
seed = 7
checker_px = 16
checker_metres = 0.25
stall_after_frames = 100
[source.replay]
path = "clips/in.y4m"
format = "raw"
loop = true
first_index = 3
[source.v4l2]
device = "/dev/video4"
buffers = 6
no_signal_timeout = 1.5
[[sink]]
kind = "snapshot"
path = "snap-%04d.jpg"
every = 5
jpeg_quality = 70
queue_depth = 2
drop = "newest"
buffers = 3
[[sink]]
kind = "null"
)",
                                          base);
    EXPECT_EQ(config.daemon.logLevel, LogLevel::Warning);
    EXPECT_EQ(config.daemon.statsIntervalSec, 2.5);
    EXPECT_EQ(config.source.kind, SourceKind::Replay);
    EXPECT_EQ(config.source.pixelFormat->name, "NV12");
    EXPECT_EQ(config.source.height, 480u);
    EXPECT_EQ(config.source.fps, 12.5);
    EXPECT_EQ(config.source.colorimetry, (Colorimetry{YcbcrMatrix::Bt709, ColourRange::Full}));
    EXPECT_EQ(config.source.synthetic.pattern, SyntheticPattern::Noise);
    EXPECT_EQ(config.source.synthetic.seed, 7u);
    EXPECT_EQ(config.source.synthetic.checkerPx, 16u);
    EXPECT_EQ(config.source.synthetic.checkerMetres, 0.25);
    EXPECT_EQ(config.source.synthetic.stallAfterFrames, 100u);
    EXPECT_EQ(config.source.replay.path, base + "/clips/in.y4m"); // inputs resolve against the config
    EXPECT_EQ(config.source.replay.format, ReplayFormat::Raw);
    EXPECT_TRUE(config.source.replay.loop);
    EXPECT_EQ(config.source.replay.firstIndex, 3u);
    EXPECT_EQ(config.source.v4l2.device, "/dev/video4");
    EXPECT_EQ(config.source.v4l2.bufferCount, 6u);
    EXPECT_EQ(config.source.v4l2.noSignalTimeoutSec, 1.5);
    ASSERT_EQ(config.sinks.size(), 2u);
    EXPECT_EQ(config.sinks[0].kind, SinkKind::Snapshot);
    EXPECT_EQ(config.sinks[0].path, "snap-%04d.jpg"); // outputs stay relative to the working directory
    EXPECT_EQ(config.sinks[0].every, 5u);
    EXPECT_EQ(config.sinks[0].jpegQuality, 70u);
    EXPECT_EQ(config.sinks[0].queueDepth, 2u);
    EXPECT_EQ(config.sinks[0].dropPolicy, DropPolicy::DropNewest);
    EXPECT_EQ(config.sinks[0].bufferCount, 3u);
    EXPECT_EQ(config.sinks[1].kind, SinkKind::Null);
}

TEST(Schema, FramesWithQuaternionAnglesAndScale)
{
    const DaemonConfig config = loadValid(R"(
[[frame]]
name = "a"
translation = [1, 2, 3]
rotation = [2, 0, 0, 0]
scale = 2
[[frame]]
name = "b"
parent = "a"
yaw = 90
scale = [1, 2, 3]
)");
    ASSERT_EQ(config.scene.frames.size(), 2u);
    EXPECT_EQ(config.scene.frames[0].transform.translation, glm::dvec3(1, 2, 3));
    EXPECT_EQ(config.scene.frames[0].transform.rotation, glm::dquat(1, 0, 0, 0)); // normalized
    EXPECT_EQ(config.scene.frames[0].transform.scale, glm::dvec3(2));
    EXPECT_EQ(config.scene.frames[1].parent, "a");
    // yaw 90 about Z: the quaternion (cos 45, 0, 0, sin 45).
    EXPECT_NEAR(config.scene.frames[1].transform.rotation.w, std::sqrt(0.5), 1e-15);
    EXPECT_NEAR(config.scene.frames[1].transform.rotation.z, std::sqrt(0.5), 1e-15);
    EXPECT_EQ(config.scene.frames[1].transform.scale, glm::dvec3(1, 2, 3));
}

TEST(Schema, StyleColourForms)
{
    const DaemonConfig config = loadValid(R"(
[[annotation]]
type = "crosshair"
style = { colour = "#102030", width = 1.5, dash = [4, 2], antialias = false, layer = "hud" }
[[annotation]]
type = "crosshair"
style = { colour = "#10203040" }
[[annotation]]
type = "crosshair"
style = { colour = [1, 2, 3, 4] }
[[annotation]]
type = "crosshair"
style = { colour = "magenta" }
)");
    const auto &a = config.scene.annotations;
    ASSERT_EQ(a.size(), 4u);
    EXPECT_EQ(a[0].style.colour.g, 0x20);
    EXPECT_EQ(a[0].style.colour.a, 255);
    EXPECT_EQ(a[0].style.width, 1.5);
    EXPECT_EQ(a[0].style.dash, (std::vector<double>{4, 2}));
    EXPECT_FALSE(a[0].style.antialias);
    EXPECT_EQ(a[0].style.layer, "hud");
    EXPECT_EQ(a[1].style.colour.a, 0x40);
    EXPECT_EQ(a[2].style.colour.b, 3);
    EXPECT_EQ(a[2].style.colour.a, 4);
    EXPECT_EQ(a[3].style.colour.r, 255);
    EXPECT_EQ(a[3].style.colour.g, 0);
}

TEST(Schema, EveryAnnotationType)
{
    const DaemonConfig config = loadValid(R"(
[[frame]]
name = "car"
[[annotation]]
type = "axes"
frame = "car"
length = 2
colours = ["red", "green", "blue"]
labels = true
[[annotation]]
type = "grid"
origin = [0, 0, 0.5]
axis_u = [1, 0, 0]
axis_v = [0, 0, 1]
spacing = 0.5
extent_u = 4
extent_v = 3
major_every = 4
major_style = { width = 3 }
[[annotation]]
type = "polyline"
points = [[0, 0, 0], [1, 0, 0], [1, 1, 0]]
closed = true
[[annotation]]
type = "markers"
points = [[0, 0, 0]]
marker = "circle"
size_px = 12
[[annotation]]
type = "box"
centre = [1, 2, 0.5]
size = [2, 4, 1]
yaw = 90
[[annotation]]
type = "arc"
radius = 3
start_deg = 0
end_deg = 90
[[annotation]]
type = "label"
anchor = [1, 2, 3]
text = "here"
offset_px = [4, 5]
size_px = 18
background = "#000000"
[[annotation]]
type = "horizon"
normal = [0, 0, 1]
[[annotation]]
type = "guide-lines"
wheelbase = 3
track_width = 1.7
steering_deg = -12
length = 6
distance_marks = [0.5, 1.5]
mark_colours = ["red", "green"]
[[annotation]]
type = "frustum"
far_distance = 3
camera = { position = [0, 0, 1], yaw = 45, fov = 60, aspect = 1.5 }
[[annotation]]
type = "text"
text = "{frame}"
position = [20, 30]
[[annotation]]
type = "crosshair"
position = [100, 100]
[[annotation]]
type = "rect"
position = [1, 2]
size = [3, 4]
filled = true
)");
    const auto &a = config.scene.annotations;
    ASSERT_EQ(a.size(), 13u);
    EXPECT_EQ(a[0].frame, "car");
    EXPECT_TRUE(std::get<AxesShape>(a[0].shape).labels);
    const auto &grid = std::get<GridShape>(a[1].shape);
    EXPECT_EQ(grid.axisV, glm::dvec3(0, 0, 1));
    EXPECT_EQ(grid.extentU, 4);
    EXPECT_EQ(grid.majorEvery, 4u);
    ASSERT_TRUE(grid.majorStyle.has_value());
    EXPECT_EQ(grid.majorStyle->width, 3);
    EXPECT_TRUE(std::get<PolylineShape>(a[2].shape).closed);
    EXPECT_EQ(std::get<MarkersShape>(a[3].shape).kind, MarkerKind::Circle);
    EXPECT_NEAR(std::get<BoxShape>(a[4].shape).rotation.z, std::sqrt(0.5), 1e-15);
    EXPECT_EQ(std::get<ArcShape>(a[5].shape).endDeg, 90);
    EXPECT_EQ(std::get<LabelShape>(a[6].shape).text, "here");
    EXPECT_TRUE(std::get<LabelShape>(a[6].shape).background.has_value());
    EXPECT_EQ(std::get<HorizonShape>(a[7].shape).normal, glm::dvec3(0, 0, 1));
    EXPECT_EQ(std::get<GuideLinesShape>(a[8].shape).steeringDeg, -12);
    EXPECT_EQ(std::get<GuideLinesShape>(a[8].shape).markColours.size(), 2u);
    // The frustum's projection is gluPerspective(60 degrees, 1.5): m[1][1] = 1 / tan(30 degrees).
    const auto &frustum = std::get<FrustumShape>(a[9].shape);
    EXPECT_NEAR(frustum.projection[1][1], 1.0 / std::tan(M_PI / 6), 1e-12);
    EXPECT_NEAR(frustum.projection[0][0], 1.0 / std::tan(M_PI / 6) / 1.5, 1e-12);
    EXPECT_NEAR(glm::length(frustum.pose.position() - glm::dvec3(0, 0, 1)), 0.0, 1e-12);
    EXPECT_EQ(std::get<ScreenTextShape>(a[10].shape).position, glm::dvec2(20, 30));
    EXPECT_EQ(std::get<CrosshairShape>(a[11].shape).position, glm::dvec2(100, 100));
    EXPECT_TRUE(std::get<RectShape>(a[12].shape).filled);
}

TEST(Schema, PoseAndIntrinsicsFormsMustNotMix)
{
    auto problems = loadInvalid("[camera]\neye = [0, 0, 1]\ntarget = [0, 1, 1]\nyaw = 10\n");
    ASSERT_FALSE(problems.empty());
    EXPECT_NE(problems[0].message.find("two pose forms"), std::string::npos) << problems[0].format();
    problems = loadInvalid("[camera]\nposition = [0, 0, 1]\nyaw = 10\ntvec = [0, 0, 0]\n");
    ASSERT_EQ(problems.size(), 1u);
    EXPECT_EQ(problems[0].key, "camera.tvec");
    EXPECT_EQ(problems[0].line, 4u);
    problems = loadInvalid("[camera]\nposition = [0, 0, 1]\nyaw = 0\nfov = 60\n[camera.frustum]\nleft = -1\n");
    ASSERT_FALSE(problems.empty());
    EXPECT_NE(problems[0].message.find("two intrinsics forms"), std::string::npos) << problems[0].format();
}

TEST(Schema, UnknownFramesAndAnnotationKeysForTheirType)
{
    const auto problems =
        loadInvalid("[[annotation]]\ntype = \"grid\"\nradius = 2\n"
                    "[camera]\nframe = \"rigg\"\nposition = [0, 0, 1]\nyaw = 0\n[[frame]]\nname = \"rig\"\n");
    ASSERT_EQ(problems.size(), 2u);
    EXPECT_EQ(problems[0].key, "annotation[0].radius");
    EXPECT_EQ(problems[1].key, "camera.frame");
    EXPECT_NE(problems[1].message.find("did you mean 'rig'?"), std::string::npos);
}

// The pixel format is resolved once, here: an unknown name is a problem at its line and key, with a suggestion.
TEST(Schema, UnknownPixelFormatNamesTheLineAndKey)
{
    const auto problems = loadInvalid("[source]\nkind = \"synthetic\"\nformat = \"NV21x\"\n");
    ASSERT_EQ(problems.size(), 1u);
    EXPECT_EQ(problems[0].line, 3);
    EXPECT_EQ(problems[0].key, "source.format");
    EXPECT_NE(problems[0].message.find("unknown pixel format 'NV21x'"), std::string::npos) << problems[0].message;
    EXPECT_NE(problems[0].message.find("did you mean 'NV21'?"), std::string::npos) << problems[0].message;
}

TEST(Schema, FarInfinityOnlyWhereTheModelAllowsIt)
{
    // The the viewing pipeline window model needs a finite far plane (S_far); projection/ says so at the window key.
    const auto problems =
        loadInvalid("[camera]\nposition = [0, 0, 1]\nyaw = 0\nfar = \"inf\"\n[camera.window]\nfocal = 1\n"
                    "half_width = 1\nhalf_height = 1\n");
    ASSERT_EQ(problems.size(), 1u);
    EXPECT_EQ(problems[0].key, "camera.window");
}

TEST(Problems, EditDistanceAndSuggestions)
{
    EXPECT_EQ(editDistance("kitten", "sitting"), 3u);
    EXPECT_EQ(editDistance("widht", "width"), 1u); // a transposition is one edit
    EXPECT_EQ(editDistance("", "abc"), 3u);
    EXPECT_EQ(editDistance("width", "width"), 0u);
    EXPECT_EQ(closestMatch("widht", {"height", "width", "fps"}), "width");
    EXPECT_EQ(closestMatch("zzzzzz", {"height", "width", "fps"}), "");
    const ConfigProblem p{"a.toml", 3, 7, "source.fps", "must be > 0"};
    EXPECT_EQ(p.format(), "a.toml:3:7: source.fps: must be > 0");
}

} // namespace
} // namespace overlayd::test
