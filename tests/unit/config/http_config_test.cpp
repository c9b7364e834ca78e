// SPDX-License-Identifier: Apache-2.0
// [http] and the HTTP API's camera requests, read by the config file's readers: defaults, every refusal at its key,
// the drop-in `POST /api/save` writes read back over the main file.
#include <filesystem>
#include <fstream>

#include "config/camera_request.h"
#include "config/live_drop_in.h"
#include "config_test_util.h"
#include "http/http_options.h"
#include "http/listen_address.h"
#include "projection/pose.h"

using namespace overlayd;
using overlayd::test::loadInvalid;
using overlayd::test::loadValid;

namespace {

const std::string kBase = test::kMinimalConfig;

// Reports every problem when the expected one is missing.
bool hasProblem(const std::vector<ConfigProblem> &problems, const std::string &key, const std::string &words)
{
    if (test::hasProblem(problems, key, words))
        return true;
    ADD_FAILURE() << "no problem at " << key << " saying '" << words << "' in:\n" << test::formatProblems(problems);
    return false;
}

// Without the server (OVERLAYD_HTTP=OFF) [http] is refused whole at its key: the tests of its keys do not apply.
constexpr const char *kWithoutServer = "built without the HTTP server (OVERLAYD_HTTP)";

std::filesystem::path scratch(const std::string &name)
{
    const auto dir = std::filesystem::temp_directory_path() / ("overlayd-http-config-" + name);
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

bool samePose(const Pose &a, const Pose &b)
{
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r)
            if (std::abs(a.rotation[c][r] - b.rotation[c][r]) > 1e-12)
                return false;
    return glm::length(a.translation - b.translation) <= 1e-12;
}

std::string fileText(const std::string &path)
{
    std::ifstream in(path);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

} // namespace

TEST(HttpConfig, AbsentMeansNoServerAndTheDefaultsAreTheDocumentedOnes)
{
    if (!httpBuiltIn())
        GTEST_SKIP() << kWithoutServer;
    EXPECT_FALSE(loadValid(kBase).http.enabled);
    const DaemonConfig config = loadValid(kBase + "[http]\ncontrol = \"off\"\n");
    EXPECT_TRUE(config.http.enabled);
    EXPECT_EQ(config.http.listen, "127.0.0.1:8080");
    EXPECT_EQ(config.http.maxClients, 32u);
    EXPECT_EQ(config.http.streamFps, 15.0);
    EXPECT_EQ(config.http.jpegQuality, 80);
}

TEST(HttpConfig, EveryBadValueIsRefusedAtItsKey)
{
    if (!httpBuiltIn())
        GTEST_SKIP() << kWithoutServer;
    const auto problems = loadInvalid(kBase + R"([http]
listen = "0.0.0.0:http"
max_clients = 0
stream_fps = 0.0
jpeg_quality = 101
control = "opne"
streem_fps = 3
)");
    hasProblem(problems, "http.listen", "port");
    hasProblem(problems, "http.max_clients", "");
    hasProblem(problems, "http.stream_fps", "");
    hasProblem(problems, "http.jpeg_quality", "");
    hasProblem(problems, "http.control", "did you mean 'open'");
    hasProblem(problems, "http.streem_fps", "did you mean 'stream_fps'");
    hasProblem(problems, "http.token_file", "missing");
}

TEST(HttpConfig, AnOpenControlApiOnlyListensLocally)
{
    if (!httpBuiltIn())
        GTEST_SKIP() << kWithoutServer;
    EXPECT_TRUE(loadValid(kBase + "[http]\nlisten = \"127.0.0.1:9000\"\ncontrol = \"open\"\n").http.enabled);
    EXPECT_TRUE(loadValid(kBase + "[http]\nlisten = \"unix:/run/o.sock\"\ncontrol = \"open\"\n").http.enabled);
    EXPECT_TRUE(loadValid(kBase + "[http]\nlisten = \"[::1]:9000\"\ncontrol = \"open\"\n").http.enabled);
    for (const char *listen : {"0.0.0.0:9000", "[::]:9000", "192.168.1.2:80"})
        hasProblem(loadInvalid(kBase + "[http]\nlisten = \"" + listen + "\"\ncontrol = \"open\"\n"), "http.control",
                   "only on loopback");
}

TEST(HttpConfig, TheTokenFileIsResolvedBesideTheConfigAndMustBeReadable)
{
    if (!httpBuiltIn())
        GTEST_SKIP() << kWithoutServer;
    const auto dir = scratch("token");
    std::ofstream(dir / "front.token") << "abc\n";
    const DaemonConfig config = loadValid(kBase + "[http]\ntoken_file = \"front.token\"\n", dir.string());
    EXPECT_EQ(config.http.tokenFile, (dir / "front.token").string());
    hasProblem(loadInvalid(kBase + "[http]\ntoken_file = \"absent.token\"\n", dir.string()), "http.token_file",
               "cannot read");
}

TEST(HttpConfig, WithoutTheServerHttpIsRefusedAtItsKey)
{
    if (httpBuiltIn())
        GTEST_SKIP() << "built with the HTTP server";
    const auto problems = loadInvalid(kBase + "[http]\ncontrol = \"off\"\n");
    ASSERT_EQ(problems.size(), 1u) << test::formatProblems(problems);
    EXPECT_EQ(problems[0].key, "http");
    EXPECT_NE(problems[0].message.find("OVERLAYD_HTTP"), std::string::npos) << problems[0].message;
}

TEST(ListenAddress, ParsesEveryFormAndRefusesTheRest)
{
    EXPECT_EQ(parseListenAddress("127.0.0.1:8080")->port, 8080u);
    EXPECT_EQ(parseListenAddress("[::1]:80")->kind, ListenAddress::Kind::Ipv6);
    EXPECT_EQ(parseListenAddress("unix:/run/x.sock")->host, "/run/x.sock");
    EXPECT_EQ(parseListenAddress("localhost:1")->host, "127.0.0.1");
    for (const char *bad : {"", "8080", "127.0.0.1", "127.0.0.1:0", "127.0.0.1:65536", "host.example:80", "[::1:80",
                            "unix:relative.sock", "1.2.3:80", "127.0.0.1:80x"})
        EXPECT_FALSE(parseListenAddress(bad).ok()) << bad;
    EXPECT_TRUE(parseListenAddress("127.5.0.1:1")->isLocal());
    EXPECT_FALSE(parseListenAddress("10.0.0.1:1")->isLocal());
}

// The API's camera requests go through [camera]'s readers: any pose form, intrinsics over the live camera.
TEST(CameraRequest, AnyPoseFormReplacesThePoseAndKeepsTheIntrinsics)
{
    const DaemonConfig config = loadValid(kBase);
    auto moved = cameraFromJson(R"({"eye": [1, -5, 2], "target": [0, 0, 0]})", config.camera, 640, 480);
    ASSERT_TRUE(moved.ok()) << moved.error().message;
    EXPECT_EQ(moved->pose, *poseLookAt({1, -5, 2}, {0, 0, 0}, {0, 0, 1}));
    EXPECT_EQ(moved->fovDeg, config.camera.fovDeg);
    auto zoomed = cameraFromJson(R"({"fov": 40})", config.camera, 640, 480);
    ASSERT_TRUE(zoomed.ok()) << zoomed.error().message;
    EXPECT_EQ(zoomed->fovDeg, 40.0);
    EXPECT_EQ(zoomed->pose, config.camera.pose);
}

TEST(CameraRequest, RefusalsNameTheKeyInTheConfigFilesWords)
{
    const DaemonConfig config = loadValid(kBase);
    const auto refused = [&](const std::string &json) {
        auto result = cameraFromJson(json, config.camera, 640, 480);
        EXPECT_FALSE(result.ok()) << json;
        return result.ok() ? std::string() : result.error().message;
    };
    EXPECT_NE(refused("{").find("not JSON"), std::string::npos);
    EXPECT_NE(refused(R"({"position": [8E88885, 0, 1]})").find("not JSON"), std::string::npos); // beyond double
    EXPECT_NE(refused("{}").find("JSON object"), std::string::npos);
    EXPECT_NE(refused(R"({"eye": [0,0,1], "gaze": [0,0,1], "up": [0,0,1]})").find("camera.up"), std::string::npos);
    EXPECT_NE(refused(R"({"position": [0,0,1], "yaw": 1, "pitch": "x"})").find("camera.pitch"), std::string::npos);
    EXPECT_NE(refused(R"({"position": [0,0,1], "yw": 1})").find("did you mean 'yaw'"), std::string::npos);
    EXPECT_NE(refused(R"({"calibration": "/etc/passwd"})").find("camera.calibration"), std::string::npos);
    EXPECT_NE(refused(R"({"fov": 180})").find("camera.fov"), std::string::npos);
    // Accepted, this would be saved as "height = 0", which the next start refuses.
    EXPECT_NE(refused(R"({"pinhole": {"fx": 500, "fy": 500, "cx": 319.5, "cy": 239.5, "width": 2}})")
                  .find("camera.pinhole.width: width and height go together"),
              std::string::npos);
    std::string deep = "{\"a\":" + std::string(20, '[') + std::string(20, ']') + "}";
    EXPECT_NE(refused(deep).find("nested"), std::string::npos);
}

TEST(LiveDropIn, IsReadAfterTheMainFileAndReplacesItsPose)
{
    const auto dir = scratch("dropin");
    const std::string path = (dir / "front.toml").string();
    std::ofstream(path) << kBase;
    EXPECT_EQ(liveDropInPath(path), (dir / "front.live.toml").string());

    std::vector<ConfigProblem> problems;
    const DaemonConfig before = *loadConfigFile(path, problems);
    const CameraSpec live =
        *cameraFromJson(R"({"eye": [2, -4, 1.5], "target": [0, 1, 0], "fov": 45})", before.camera, 640, 480);
    std::ofstream(liveDropInPath(path)) << *liveDropInText(live, "", "a test");
    auto after = loadConfigFile(path, problems);
    ASSERT_TRUE(after.ok()) << after.error().message;
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r)
            EXPECT_NEAR(after->camera.pose.rotation[c][r], live.pose.rotation[c][r], 1e-12);
    EXPECT_LT(glm::length(after->camera.pose.translation - live.pose.translation), 1e-12);
    EXPECT_EQ(after->camera.fovDeg, 45.0);
    EXPECT_EQ(after->camera.near, before.camera.near);

    // A broken drop-in is reported at its own file and line.
    std::ofstream(liveDropInPath(path)) << "[camera]\nposition = [1, 2]\norientation = [1, 0, 0, 0]\n";
    EXPECT_FALSE(loadConfigFile(path, problems).ok());
    ASSERT_FALSE(problems.empty());
    EXPECT_EQ(problems.front().file, liveDropInPath(path));
    EXPECT_EQ(problems.front().line, 2u);
    EXPECT_EQ(problems.front().key, "camera.position");
}

// The whole camera goes into the drop-in and comes back equal, field for field, for every intrinsics form; what the
// drop-in held that the save does not write is kept, what it replaces is gone.
TEST(LiveDropIn, KeepsTheWholeCameraAndMergesWithWhatTheDropInHolds)
{
    const auto dir = scratch("whole");
    const std::string path = (dir / "front.toml").string();
    std::ofstream(path) << kBase;
    std::vector<ConfigProblem> problems;
    const DaemonConfig before = *loadConfigFile(path, problems);
    const char *changes[] = {
        R"({"fov": 47.123456789012345, "fov_axis": "horizontal", "near": 0.37, "far": "inf", "depth_range": "0..1"})",
        R"({"pinhole": {"fx": 501.1, "fy": 499.9, "cx": 320.3, "cy": 239.7, "skew": 0.1},
            "distortion": {"model": "rational_polynomial", "coefficients": [-0.2, 0.03, 0.001, -0.0008, 0.002, 0.01]}})",
        R"({"pinhole": {"fx": 1001.0, "fy": 1001.0, "cx": 640.5, "cy": 400.5, "width": 1280, "height": 800},
            "calibration_crop": [106, 0, 1067, 800], "distortion": {"model": "equidistant", "coefficients": [0.1]}})",
        R"({"frustum": {"left": -0.06, "right": 0.055, "bottom": -0.033, "top": 0.031}, "near": 0.05})",
        R"({"window": {"focal": 1.5, "centre": [0.01, -0.02], "half_width": 0.8, "half_height": 0.6}})",
        R"({"orthographic": {"left": -8, "right": 8, "bottom": -6, "top": 6}, "far": 80})",
        R"({"orthographic": {"width": 16, "height": 12}, "far": 80})",
        R"({"eye": [2, -4, 1.5], "target": [0, 1, 0], "up": [0.1, 0, 1]})",
    };
    for (const char *change : changes) {
        auto live = cameraFromJson(change, before.camera, 640, 480);
        ASSERT_TRUE(live.ok()) << change << ": " << live.error().message;
        std::ofstream(liveDropInPath(path)) << "# by hand\n[camera]\nframe = \"world\"\nfov = 33.0\nnear = 9.0\n";
        auto written = writeLiveDropIn(path, *live, "a test");
        ASSERT_TRUE(written.ok()) << written.error().message;
        auto after = loadConfigFile(path, problems);
        ASSERT_TRUE(after.ok()) << change << ": " << after.error().message;
        // A look-at pose goes back as eye/target/up: its basis is rebuilt from them, equal to within rounding.
        CameraSpec loaded = after->camera;
        EXPECT_TRUE(samePose(loaded.pose, live->pose)) << change;
        loaded.pose = live->pose;
        EXPECT_TRUE(loaded == *live) << change;
        std::ifstream saved(liveDropInPath(path));
        const std::string text((std::istreambuf_iterator<char>(saved)), std::istreambuf_iterator<char>());
        EXPECT_NE(text.find("frame = \"world\""), std::string::npos) << text;
        EXPECT_NE(text.find("(a test)"), std::string::npos) << text;
    }
    // A drop-in that is not TOML is not saved over.
    std::ofstream(liveDropInPath(path)) << "[camera\n";
    auto refused = writeLiveDropIn(path, before.camera, "a test");
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.error().message.find("front.live.toml:1"), std::string::npos) << refused.error().message;
}

// A file or link planted at a predictable temporary name neither redirects the save nor is touched by it.
TEST(LiveDropIn, APlantedTemporaryIsNeitherFollowedNorTouched)
{
    const auto dir = scratch("planted");
    const std::string path = (dir / "front.toml").string();
    std::ofstream(path) << kBase;
    std::vector<ConfigProblem> problems;
    const DaemonConfig config = *loadConfigFile(path, problems);
    const auto victim = dir / "victim.txt", planted = dir / "front.live.toml.tmp";
    std::ofstream(victim) << "untouched\n";
    std::filesystem::create_symlink(victim, planted);
    ASSERT_TRUE(writeLiveDropIn(path, config.camera, "a test").ok());
    std::ifstream in(victim);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(text, "untouched\n");
    EXPECT_TRUE(std::filesystem::is_symlink(planted));
    EXPECT_FALSE(std::filesystem::is_symlink(liveDropInPath(path)));
    std::filesystem::remove(planted);
    std::filesystem::create_directory(planted);
    EXPECT_TRUE(writeLiveDropIn(path, config.camera, "a test").ok());
    size_t entries = 0;
    for ([[maybe_unused]] const auto &entry : std::filesystem::directory_iterator(dir))
        ++entries;
    EXPECT_EQ(entries, 4u); // the config, the drop-in, the victim, the planted folder: no temporary left
}

// A save writes the live pose in the pose keys the config used, whatever form the API's edit came in: the user's
// degrees stay degrees (`yaw = 95.0`, not a matrix), a look-at stays eye/target, an optical quaternion stays one.
TEST(LiveDropIn, WritesThePoseInTheConfigsOwnForm)
{
    struct Form {
        const char *keys;                        // the main file's pose
        std::vector<std::string> written, never; // in the drop-in's [camera], and not
    };
    const Form forms[] = {
        {"position = [0.0, -6.0, 3.0]\nyaw = 90.0\npitch = 25.0\n",
         {"position = [0.5, -6.0, 3.0]", "yaw = 95.0", "pitch = 20.0", "roll = 0.0"},
         {"rmat", "tvec"}},
        {"eye = [0.0, -6.0, 3.0]\ntarget = [0.0, 4.0, 0.0]\n",
         {"eye = [0.5, -6.0, 3.0]", "target = ", "up = "},
         {"rmat", "yaw"}},
        {"eye = [0.0, -6.0, 3.0]\ngaze = [0.0, 1.0, -0.3]\n", {"eye = [0.5, -6.0, 3.0]", "gaze = ", "up = "}, {"rmat"}},
        {"prp = [0.0, -6.0, 3.0]\nvpn = [0.0, -1.0, 0.3]\n", {"prp = [0.5, -6.0, 3.0]", "vpn = ", "vup = "}, {"rmat"}},
        {"position = [0.0, -6.0, 3.0]\norientation = [0.5, -0.5, 0.5, -0.5]\naxes = \"optical\"\n",
         {"position = [0.5, -6.0, 3.0]", "orientation = ", "axes = \"optical\""},
         {"rmat", "yaw"}},
        {"rvec = [1.9, 0.1, -0.05]\ntvec = [0.2, 1.1, 6.3]\n", {"rvec = ", "tvec = "}, {"rmat", "yaw"}},
        {"rmat = [[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]]\ntvec = [0.0, 2.0, 7.0]\n",
         {"rmat = ", "tvec = "},
         {"yaw", "rvec"}},
    };
    const auto dir = scratch("form");
    const std::string path = (dir / "front.toml").string();
    for (const Form &form : forms) {
        std::ofstream(path) << "[source]\nkind = \"synthetic\"\nwidth = 640\nheight = 480\n[camera]\nfov = 60.0\n"
                            << form.keys;
        std::filesystem::remove(liveDropInPath(path));
        std::vector<ConfigProblem> problems;
        auto before = loadConfigFile(path, problems);
        ASSERT_TRUE(before.ok()) << form.keys << before.error().message;
        // The page's edit: position and degrees, in another form than the file's.
        auto live = cameraFromJson(R"({"position": [0.5, -6.0, 3.0], "yaw": 95, "pitch": 20, "roll": 0})",
                                   before->camera, 640, 480);
        ASSERT_TRUE(live.ok()) << live.error().message;
        ASSERT_TRUE(writeLiveDropIn(path, *live, "a test").ok());
        const std::string text = fileText(liveDropInPath(path));
        const std::string camera = text.substr(text.find("[camera]"));
        for (const std::string &key : form.written)
            EXPECT_NE(camera.find(key), std::string::npos) << form.keys << "wrote:\n" << text;
        for (const std::string &key : form.never)
            EXPECT_EQ(camera.find(key), std::string::npos) << form.keys << "wrote:\n" << text;
        auto after = loadConfigFile(path, problems);
        ASSERT_TRUE(after.ok()) << text << after.error().message;
        EXPECT_TRUE(samePose(after->camera.pose, live->pose)) << text;
        const PoseKeysUsed &was = before->camera.poseKeys, &is = after->camera.poseKeys;
        EXPECT_TRUE(is.form == was.form && is.axes == was.axes) << text;
        EXPECT_NEAR(is.targetDistance, was.targetDistance, 1e-9) << text; // a look-at keeps its target's distance
    }
}
