// SPDX-License-Identifier: Apache-2.0
// The zero-copy test rig: a fake camera and a fake output in one fake kernel, the source and the sink wired to them.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "drivers/v4l2/output_sink.h"
#include "test_devices.h"

namespace overlayd::test {

struct ZeroCopyRig {
    CaptureRig rig;
    FakeDevice *camera = nullptr, *output = nullptr;
    std::vector<std::string> sinkLog;
    std::unique_ptr<V4l2OutputSink> sink;
    StreamFormat stream{};

    ZeroCopyRig()
    {
        camera = &addYuyvCamera(rig.kernel);
        output = &rig.kernel.add("/dev/video10");
        output->card = "Out";
        output->bufferType = V4L2_BUF_TYPE_VIDEO_OUTPUT;
        output->formats = {{V4L2_PIX_FMT_YUYV, {{640, 480}}, {30.0}}};
    }

    void startCapture(bool exportDmabuf = true, const std::string &format = "YUYV")
    {
        SourceOptions options = captureOptions(format, 640, 480, 30.0);
        options.v4l2.exportDmabuf = exportDmabuf;
        rig.make(options);
        auto started = rig.source->start();
        ASSERT_TRUE(started.ok()) << started.error().message;
        stream = *started;
    }

    Status openSink(ZeroCopy mode, unsigned buffers = 4)
    {
        SinkOptions options;
        options.kind = SinkKind::V4l2Output;
        options.path = "/dev/video10";
        options.bufferCount = buffers;
        options.zeroCopy = mode;
        sink = std::make_unique<V4l2OutputSink>(rig.kernel, options,
                                                [this](const std::string &line) { sinkLog.push_back(line); });
        return sink->open(stream);
    }

    // The camera fills its next buffer with `value` everywhere; the frame comes back as a shared lease.
    std::shared_ptr<const FrameLease> capture(uint32_t sequence, uint8_t value)
    {
        EXPECT_TRUE(camera->produce(sequence, std::chrono::microseconds(0), [value](FakeDevice::Buffer &b) {
            for (auto &plane : b.planes)
                std::fill(plane.begin(), plane.end(), value);
        }));
        auto lease = rig.source->nextFrame();
        EXPECT_TRUE(lease.ok()) << lease.error().message;
        return lease ? std::make_shared<const FrameLease>(std::move(lease.value())) : nullptr;
    }
};

} // namespace overlayd::test
