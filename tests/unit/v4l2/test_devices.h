// SPDX-License-Identifier: Apache-2.0
// Ready-made fake cameras for the V4L2 tests, and a source wired to one with its log captured.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "drivers/v4l2/capture_source.h"
#include "fake_v4l2.h"

namespace overlayd::test {

// A webcam offering YUYV at 640x480 and 1280x720, 15 and 30 fps.
inline FakeDevice &addYuyvCamera(FakeSyscalls &kernel, const std::string &path = "/dev/video0")
{
    FakeDevice &device = kernel.add(path);
    device.formats = {{V4L2_PIX_FMT_YUYV, {{640, 480}, {1280, 720}}, {15.0, 30.0}}};
    return device;
}

inline SourceOptions captureOptions(const std::string &format, unsigned width, unsigned height, double fps,
                                    const std::string &device = "/dev/video0")
{
    SourceOptions options;
    options.kind = SourceKind::V4l2;
    options.pixelFormat = pixelFormatFromName(format);
    options.width = width;
    options.height = height;
    options.fps = fps;
    options.v4l2.device = device;
    options.v4l2.bufferCount = 4;
    return options;
}

struct CaptureRig {
    FakeSyscalls kernel;
    std::vector<std::string> log;
    std::unique_ptr<V4l2CaptureSource> source;

    void make(const SourceOptions &options)
    {
        source = std::make_unique<V4l2CaptureSource>(kernel, options,
                                                     [this](const std::string &line) { log.push_back(line); });
    }
};

} // namespace overlayd::test
