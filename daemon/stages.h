// SPDX-License-Identifier: Apache-2.0
// StageFactories: how the daemon builds its source, sinks and overlay from a config. The real ones call the
// drivers' and overlay's factories; tests substitute fakes.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "config/daemon_config.h"
#include "control/scene_control.h"
#include "drivers/frame_sink.h"
#include "drivers/frame_source.h"
#include "gpio/line_provider.h"
#include "overlay/overlay_renderer.h"
#include "stream/encoded_stream_engine.h"

namespace overlayd {

// `sceneCamera`: the stream's camera when the source draws through it (drawsThroughCamera), else null.
using SourceFactory =
    std::function<Result<std::unique_ptr<FrameSource>>(const SourceOptions &options, const Camera *sceneCamera)>;

struct StageFactories {
    SourceFactory source;
    std::function<Result<std::unique_ptr<FrameSink>>(const SinkOptions &)> sink;
    // May return a null renderer: nothing to draw. SceneControl calls it with the live scene and camera.
    RendererFactory renderer;
    // Where GPIO lines come from (libgpiod); null: no [[gpio.*]] line can be requested.
    std::function<std::unique_ptr<LineProvider>()> gpio;
    // The encoded outputs' engine (the GStreamer module, loaded on first use); asked only when an encoded sink is
    // configured.
    std::function<Result<std::unique_ptr<EncodedStreamEngine>>(const StreamOptions &, const EngineLog &)> streamEngine;
};

// makeSource, makeSink, and SceneRenderer::create for the negotiated stream.
StageFactories defaultStageFactories();

// Whether the source renders its frames through the stream's camera (the synthetic checkerboard scene).
bool drawsThroughCamera(const SourceOptions &options);
// Whether a V4L2 output sink or a V4L2 encoder may take the capture buffers themselves (zero_copy not "off"): then the
// V4L2 source exports its buffers (VIDIOC_EXPBUF), and a reload that changes this re-opens the source.
bool wantsZeroCopy(const DaemonConfig &config);
// Only one sink may hold the camera's buffers (it may hold all but the 2 the capture keeps): the first v4l2 sink
// with zero_copy = "on", else the first with "auto", keeps zero copy; the other "auto" ones are turned "off" (one
// notice each). Two "on" sinks are a ConfigError.
Status limitZeroCopy(std::vector<SinkOptions> &sinks, std::vector<std::string> &notices);
// The encoder does not hold the camera's buffers beside a V4L2 output sink that does (limitZeroCopy's outcome): its
// "auto" turns "off" (a notice), "on" with such a sink is a ConfigError.
Status limitEncoderZeroCopy(const std::vector<SinkOptions> &sinks, EncoderOptions &encoder,
                            std::vector<std::string> &notices);
// Whether the source draws through [camera] (the synthetic checkerboard scene) and that camera changed, so that a
// reload must re-open the source although its own options are the same (whole CameraSpecs compared).
bool sceneCameraChanged(const DaemonConfig &a, const DaemonConfig &b);
// Whether two sources may be the same device, which cannot be opened twice: a reload then closes the running one
// before it opens the new one. V4L2 devices are the same unless both names resolve to different device files (a
// card name or a by-id link may name the running device); libcamera cameras always may be (an index and an id can
// name one camera); synthetic and replay sources never are.
bool mayShareDevice(const SourceOptions &running, const SourceOptions &next);

} // namespace overlayd
