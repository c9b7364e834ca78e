// SPDX-License-Identifier: Apache-2.0
// What a user can configure about a frame source, and the one factory that builds any of them.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "base/result.h"
#include "drivers/frame_source.h"
#include "media/colorimetry.h"
#include "media/pixel_format.h"
#include "projection/camera.h"

namespace overlayd {

enum class SourceKind { Synthetic, Replay, V4l2, Libcamera };

// Deterministic patterns; CheckerboardScene renders a checkerboard ground plane (z = 0 in world) through the
// stream's camera, per pixel, by unprojecting a ray and intersecting the plane.
enum class SyntheticPattern { ColourBars, Checkerboard, MovingGradient, Noise, CheckerboardScene };

struct SyntheticOptions {
    SyntheticPattern pattern = SyntheticPattern::CheckerboardScene;
    uint64_t seed = 1;          // Noise
    unsigned checkerPx = 40;    // Checkerboard: square size in pixels
    double checkerMetres = 1.0; // CheckerboardScene: square size on the ground (squares have corners at k * size)
    // Diagnostics and tests: after this many frames the source stops delivering (TryAgain forever, no error), as a
    // wedged camera would; the systemd watchdog must then stop being petted. 0: never.
    uint64_t stallAfterFrames = 0;

    bool operator==(const SyntheticOptions &) const = default;
};

enum class ReplayFormat { Auto, Y4m, Raw, Images }; // Auto: from the path's extension (%d in it: Images)

struct ReplayOptions {
    std::string path; // Y4M file, raw file, or an image sequence pattern such as "frames/%04d.png"
    ReplayFormat format = ReplayFormat::Auto;
    bool loop = false;
    unsigned firstIndex = 0; // Images: the number the sequence starts at

    bool operator==(const ReplayOptions &) const = default;
};

struct V4l2CaptureOptions {
    std::string device = "/dev/video0"; // a path, a /dev/v4l/by-id|by-path link, or a card name
    unsigned bufferCount = 4;
    double noSignalTimeoutSec = 2.0; // no frame for this long: the stream is torn down and retried
    // VIDIOC_EXPBUF every buffer so that frames carry dmabuf fds (zero-copy sinks). Not a config key: the daemon
    // sets it when a sink wants zero copy. A driver that refuses is logged once and streams without fds.
    bool exportDmabuf = false;

    bool operator==(const V4l2CaptureOptions &) const = default;
};

// What a libcamera camera is asked for (drivers/libcamera/). Control names and value types are checked against
// libcamera's control registry when the config is loaded; ranges against the opened camera at start.
enum class StreamRole { Viewfinder, VideoRecording, StillCapture };
enum class ImageTransform { Identity, HFlip, VFlip, Rot180 };

struct ControlSetting {
    std::string name; // libcamera's name: "Brightness", "AeEnable"
    std::variant<bool, int64_t, double> value;
    std::string where; // "file:line:column: source.libcamera.controls.NAME", so errors at start name the key

    bool operator==(const ControlSetting &) const = default;
};

struct LibcameraOptions {
    std::string camera = "0"; // an index into libcamera's list, a camera id, or a substring of the model name
    StreamRole role = StreamRole::VideoRecording;
    unsigned bufferCount = 4;
    double noSignalTimeoutSec = 2.0; // no frame for this long: the stream is torn down and retried
    std::vector<ControlSetting> controls;
    ImageTransform transform = ImageTransform::Identity;

    bool operator==(const LibcameraOptions &) const = default;
};

struct SourceOptions {
    SourceKind kind = SourceKind::Synthetic;
    // The requested stream. Raw replay and synthetic sources produce exactly this; Y4M and images take size and
    // (for Y4M) format from the file; V4L2 negotiates (Valid / Adjusted / Invalid).
    // Resolved from its name once, by the config loader; never null.
    const PixelFormatInfo *pixelFormat = pixelFormatFromName("YUYV");
    unsigned width = 1280, height = 720;
    double fps = 30.0;
    std::optional<Colorimetry> colorimetry; // default: BT.601 limited, or what the device reports
    SyntheticOptions synthetic;
    ReplayOptions replay;
    V4l2CaptureOptions v4l2;
    LibcameraOptions libcamera;

    // Every field: a reload re-opens the source when any differs, so a field added later is never ignored.
    bool operator==(const SourceOptions &) const = default;
};

// Whether this build has libcamera (the CMake option OVERLAYD_LIBCAMERA); without it kind = "libcamera" is refused.
bool libcameraBuiltIn();
// libcamera's control registry, for checking a config without a camera: every control's name, and what kind of
// config value one takes (nullopt: no such control). Empty / nullopt in builds without libcamera.
enum class ControlValueKind { Bool, Integer, Float, Unsupported };
std::vector<std::string> libcameraControlNames();
std::optional<ControlValueKind> libcameraControlKind(const std::string &name);
// Why the registry's control could never take the setting's value, whatever the camera (NaN or beyond the control's
// type, a single value for an array control), or empty when it could; the camera's ranges are checked when it
// opens. The same check builds the camera's controls, so check-config refuses what run would.
std::string libcameraControlProblem(const ControlSetting &setting);

// Validates before allocating anything (sizes, fps). V4L2 support may be compiled out: then asking for it is an
// Unsupported error, never a crash. `sceneCamera`: the stream's camera, which the checkerboard-scene pattern is
// rendered through (its viewport is the frame size); the other sources ignore it.
Result<std::unique_ptr<FrameSource>> makeSource(const SourceOptions &options, const Camera *sceneCamera = nullptr);

} // namespace overlayd
