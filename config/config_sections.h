// SPDX-License-Identifier: Apache-2.0
// The readers of each section of the config file, shared by the loader. Private to config/.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "config/daemon_config.h"
#include "config/toml_reader.h"

namespace overlayd {

class SceneImages;

// Where the camera's parts came from, so that errors found when composing the Camera land on the right key.
struct CameraKeys {
    std::string intrinsics = "fov"; // the key of the intrinsics form in [camera]
    bool hasDistortion = false;
};

// Every key of the pose forms, and of the intrinsics forms: the drop-in's pose or intrinsics form replaces all of
// the main file's (config_loader.cpp), a request with any pose key is a new pose (camera_request.cpp).
inline constexpr std::string_view kPoseKeys[] = {"eye",  "target",   "gaze",        "up",   "prp", "vpn",
                                                 "vup",  "position", "orientation", "axes", "yaw", "pitch",
                                                 "roll", "rvec",     "tvec",        "rmat"};
inline constexpr std::string_view kIntrinsicsFormKeys[] = {"fov",     "fov_axis", "frustum",
                                                           "pinhole", "window",   "orthographic"};

// A relative path resolved against the config file's folder.
std::string resolvePath(const std::string &baseDirectory, const std::string &path);

void readDaemon(TableReader &root, DaemonSettings &out);
void readSource(TableReader &root, const std::string &baseDirectory, SourceOptions &out);
// [[sink]]: the raw kinds into `out`, the encoded kinds (stream_config.cpp) into `encoded`.
void readSinks(TableReader &root, std::vector<SinkOptions> &out, StreamOptions &encoded);
// [encoder]: the one encode the encoded sinks share; an encoded [[sink]] (kind = "rtsp").
void readEncoder(TableReader &root, StreamOptions &out);
bool isEncodedSink(TableReader &sink);
void readEncodedSink(TableReader &sink, StreamOptions &out);
// kind = "record" and kind = "push" (record_push_config.cpp); `sofar` holds the encoded sinks read before.
void readRecord(TableReader &sink, const StreamOptions &sofar, RecordSinkOptions &out);
void readPush(TableReader &sink, PushSinkOptions &out);
// [webrtc] (webrtc_config.cpp), after [http], which serves it.
void readWebrtc(TableReader &root, bool httpEnabled, WebrtcOptions &out);
// [[gpio.input]] / [[gpio.output]], after the annotations (their layers are what inputs may switch).
void readGpio(TableReader &root, const std::vector<Annotation> &annotations, GpioOptions &out);
// [[input.text]] (after the annotations: their text slots are what inputs may feed).
void readInputs(TableReader &root, const std::string &baseDirectory, const OverlayScene &scene, InputOptions &out);
// [http]: the server's options (see http/http_options.h).
void readHttp(TableReader &root, const std::string &baseDirectory, HttpOptions &out);
// An RTSP sink's `auth` and `tls` keys (rtsp_access_config.cpp); after [http], what they resolve to: its users and
// tokens, its certificate.
void readRtspAccess(TableReader &sink, RtspAccessOptions &out);
void resolveRtspAccess(TableReader &root, const HttpOptions &http, StreamOptions &stream);

// The pose keys of a camera table (one of the forms projection/pose.h offers); false after reporting a problem.
// `used`, when given, learns which form the keys were in.
bool readPose(TableReader &camera, Pose &out, PoseKeysUsed *used = nullptr);
// Intrinsics, near/far, depth range, distortion and calibration of [camera].
void readIntrinsics(TableReader &camera, const std::string &baseDirectory, CameraSpec &out, CameraKeys &keys);
void readViewport(TableReader &viewport, ViewportSpec &out);

// A rotation as [w, x, y, z] under `quaternionKey`, or yaw/pitch/roll in degrees (Rz Ry Rx).
std::optional<glm::dquat> readRotation(TableReader &table, std::string_view quaternionKey);

void readFrames(TableReader &root, std::vector<FrameSpec> &out);
void readAnnotations(TableReader &root, const std::string &baseDirectory, std::vector<Annotation> &out);
void readShape(TableReader &table, const std::string &type, const std::string &baseDirectory, SceneImages &images,
               Shape &out);
Shape readFrustumShape(TableReader &table, const std::string &baseDirectory);
// type = "image": the file (relative to the config's folder), decoded once per scene by `images`.
Shape readImageShape(TableReader &table, const std::string &baseDirectory, SceneImages &images);
std::optional<Style> readStyle(TableReader &style, const Style &base);

} // namespace overlayd
