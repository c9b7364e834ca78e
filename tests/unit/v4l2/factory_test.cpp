// SPDX-License-Identifier: Apache-2.0
// The factory entry points on the real kernel (this machine has no V4L2 device: only the error paths run).
#include <gtest/gtest.h>

#include "drivers/sink_options.h"
#include "drivers/source_options.h"
#include "drivers/v4l2/v4l2_factory.h"
#include "test_devices.h"

namespace overlayd::test {
namespace {

TEST(V4l2Factory, BufferCountsOutOfRangeAreConfigErrors)
{
    auto options = captureOptions("YUYV", 640, 480, 30.0);
    options.v4l2.bufferCount = 1;
    EXPECT_EQ(makeV4l2Source(options).error().code, ErrorCode::ConfigError);
    SinkOptions sink;
    sink.kind = SinkKind::V4l2Output;
    sink.path = "/dev/video10";
    sink.bufferCount = 64;
    EXPECT_EQ(makeV4l2OutputSink(sink).error().code, ErrorCode::ConfigError);
}

TEST(V4l2Factory, RealKernelMissingDeviceIsNotFound)
{
    auto source = makeSource(captureOptions("YUYV", 640, 480, 30.0, "/nonexistent/video0"));
    ASSERT_TRUE(source.ok()) << source.error().message;
    EXPECT_EQ((*source)->describe(), "/nonexistent/video0");
    auto format = (*source)->start();
    ASSERT_FALSE(format.ok());
    EXPECT_EQ(format.error().code, ErrorCode::NotFound);
    EXPECT_EQ((*source)->eventFd(), -1);
}

TEST(V4l2Factory, RealKernelNonV4l2NodeIsRefused)
{
    std::vector<std::string> log;
    auto source = makeV4l2Source(captureOptions("YUYV", 640, 480, 30.0, "/dev/null"),
                                 [&](const std::string &line) { log.push_back(line); });
    ASSERT_TRUE(source.ok());
    auto format = (*source)->start();
    ASSERT_FALSE(format.ok());
    EXPECT_EQ(format.error().code, ErrorCode::Io);
    EXPECT_NE(format.error().message.find("/dev/null is not a V4L2 device"), std::string::npos);
}

TEST(V4l2Factory, RealKernelOutputSinkOnANonV4l2NodeFailsAtOpen)
{
    SinkOptions options;
    options.kind = SinkKind::V4l2Output;
    options.path = "/dev/null";
    auto sink = makeSink(options);
    ASSERT_TRUE(sink.ok()) << sink.error().message;
    auto status = (*sink)->open({pixelFormatFromName("YUYV"), 64, 32, 0, {}, 30.0});
    ASSERT_FALSE(status.ok());
    EXPECT_EQ(status.error().code, ErrorCode::Io);
}

} // namespace
} // namespace overlayd::test
