// SPDX-License-Identifier: Apache-2.0
// V4L2 output: format set to the stream's, stride-aware copies into the driver's buffers, drops, errors.
#include <gtest/gtest.h>

#include "drivers/v4l2/output_sink.h"
#include "fake_v4l2.h"
#include "media/frame_buffer.h"

namespace overlayd::test {
namespace {

struct Output : ::testing::Test {
    FakeSyscalls kernel;
    FakeDevice *device = nullptr;
    std::unique_ptr<V4l2OutputSink> sink;

    void SetUp() override
    {
        device = &kernel.add("/dev/video10");
        device->card = "Dummy video device";
        device->bufferType = V4L2_BUF_TYPE_VIDEO_OUTPUT;
        device->formats = {{V4L2_PIX_FMT_YUYV, {{64, 32}}, {30.0}}, {V4L2_PIX_FMT_NV12, {{64, 32}}, {30.0}}};
        SinkOptions options;
        options.kind = SinkKind::V4l2Output;
        options.path = "/dev/video10";
        options.bufferCount = 3;
        sink = std::make_unique<V4l2OutputSink>(kernel, options);
    }

    // A frame whose byte at (plane, row, column) is row * 3 + column, in a buffer with its own padded stride.
    static FrameBuffer pattern(const char *format, unsigned stride)
    {
        auto buffer = FrameBuffer::allocate({pixelFormatFromName(format), 64, 32, stride, {}, 30.0});
        FrameView view = buffer->view();
        for (unsigned p = 0; p < view.format->numPlanes; ++p)
            for (unsigned y = 0; y < view.format->planeHeight(p, 32); ++y)
                for (unsigned x = 0; x < view.planes[p].stride; ++x)
                    view.planes[p].data[y * view.planes[p].stride + x] =
                        x < view.format->minStride(p, 64) ? uint8_t(y * 3 + x + p) : 0xee;
        return std::move(buffer.value());
    }
};

TEST_F(Output, OpenSetsTheStreamsFormatAndColorimetry)
{
    auto status = sink->open({pixelFormatFromName("YUYV"), 64, 32, 0, {YcbcrMatrix::Bt709, ColourRange::Full}, 30});
    ASSERT_TRUE(status.ok()) << status.error().message;
    EXPECT_EQ(device->format.fmt.pix.pixelformat, uint32_t(V4L2_PIX_FMT_YUYV));
    EXPECT_EQ(device->format.fmt.pix.width, 64u);
    EXPECT_EQ(device->format.fmt.pix.ycbcr_enc, uint32_t(V4L2_YCBCR_ENC_709));
    EXPECT_EQ(device->format.fmt.pix.quantization, uint32_t(V4L2_QUANTIZATION_FULL_RANGE));
    EXPECT_TRUE(device->streaming);
    EXPECT_EQ(sink->describe(), "v4l2 output /dev/video10 (Dummy video device)");
}

TEST_F(Output, FramesAreCopiedRowByRowIntoThePaddedDriverStride)
{
    device->padding = {16, 0, 0}; // driver rows of 144 bytes; ours of 160
    ASSERT_TRUE(sink->open({pixelFormatFromName("YUYV"), 64, 32, 0, {}, 30}).ok());
    FrameBuffer frame = pattern("YUYV", 160);
    for (int i = 0; i < 5; ++i)
        ASSERT_TRUE(sink->write(frame.view(), {}).ok());
    ASSERT_EQ(device->written.size(), 5u);
    const std::vector<uint8_t> &out = device->written[4][0];
    ASSERT_EQ(out.size(), 144u * 32);
    for (unsigned y = 0; y < 32; ++y)
        for (unsigned x = 0; x < 128; ++x)
            ASSERT_EQ(out[y * 144 + x], uint8_t(y * 3 + x)) << x << "," << y;
    EXPECT_EQ(sink->writtenFrames(), 5u);
    EXPECT_EQ(sink->droppedFrames(), 0u);
}

TEST_F(Output, Nv12LandsInOneBufferAtTheDriversPlaneOffsets)
{
    device->padding = {8, 0, 0};
    ASSERT_TRUE(sink->open({pixelFormatFromName("NV12"), 64, 32, 0, {}, 30}).ok());
    FrameBuffer frame = pattern("NV12", 0);
    ASSERT_TRUE(sink->write(frame.view(), {}).ok());
    const std::vector<uint8_t> &out = device->written.at(0)[0];
    ASSERT_EQ(out.size(), 72u * 48);
    EXPECT_EQ(out[31 * 72 + 63], uint8_t(31 * 3 + 63));
    EXPECT_EQ(out[72 * 32 + 15 * 72 + 63], uint8_t(15 * 3 + 63 + 1)); // chroma row 15 after 32 luma rows
}

TEST_F(Output, MultiPlanarOutputDevice)
{
    device->bufferType = V4L2_BUF_TYPE_VIDEO_OUTPUT_MPLANE;
    device->formats = {{V4L2_PIX_FMT_NV12M, {{64, 32}}, {30.0}}, {V4L2_PIX_FMT_YUYV, {{64, 32}}, {30.0}}};
    ASSERT_TRUE(sink->open({pixelFormatFromName("YUYV"), 64, 32, 0, {}, 30}).ok());
    FrameBuffer frame = pattern("YUYV", 0);
    ASSERT_TRUE(sink->write(frame.view(), {}).ok());
    ASSERT_EQ(device->written.size(), 1u);
    EXPECT_EQ(device->written[0][0][5 * 128 + 7], uint8_t(5 * 3 + 7));
}

TEST_F(Output, Nv12GoesOutAsNv12mWhereThatIsAllTheDeviceTakes)
{
    device->bufferType = V4L2_BUF_TYPE_VIDEO_OUTPUT_MPLANE;
    device->formats = {{V4L2_PIX_FMT_YUYV, {{64, 32}}, {30.0}}, {V4L2_PIX_FMT_NV12M, {{64, 32}}, {30.0}}};
    device->padding = {16, 32, 0};
    ASSERT_TRUE(sink->open({pixelFormatFromName("NV12"), 64, 32, 0, {}, 30}).ok());
    EXPECT_EQ(device->format.fmt.pix_mp.pixelformat, uint32_t(V4L2_PIX_FMT_NV12M));
    FrameBuffer frame = pattern("NV12", 0);
    ASSERT_TRUE(sink->write(frame.view(), {}).ok());
    ASSERT_EQ(device->written.size(), 1u);
    ASSERT_EQ(device->written[0].size(), 2u);
    EXPECT_EQ(device->written[0][0].size(), 80u * 32);
    EXPECT_EQ(device->written[0][0][31 * 80 + 63], uint8_t(31 * 3 + 63));
    EXPECT_EQ(device->written[0][1].size(), 96u * 16);
    EXPECT_EQ(device->written[0][1][15 * 96 + 63], uint8_t(15 * 3 + 63 + 1));
}

TEST_F(Output, RgbStreamIsLabelledSrgbFullRange)
{
    device->formats = {{V4L2_PIX_FMT_RGB24, {{64, 32}}, {30.0}}};
    ASSERT_TRUE(sink->open({pixelFormatFromName("RGB24"), 64, 32, 0, {}, 30}).ok());
    EXPECT_EQ(device->format.fmt.pix.colorspace, uint32_t(V4L2_COLORSPACE_SRGB));
    EXPECT_EQ(device->format.fmt.pix.quantization, uint32_t(V4L2_QUANTIZATION_FULL_RANGE));
}

TEST_F(Output, RefusedFormatIsAClearError)
{
    auto status = sink->open({pixelFormatFromName("RGB24"), 64, 32, 0, {}, 30});
    ASSERT_FALSE(status.ok());
    EXPECT_EQ(status.error().code, ErrorCode::ConfigError);
    EXPECT_EQ(status.error().message,
              "/dev/video10 (Dummy video device) cannot output 64x32 RGB24 30.0 fps (it offers YUYV 64x32)");
}

TEST_F(Output, ReaderThatStopsReadingMakesDropsNotStalls)
{
    device->consumeOutput = false;
    ASSERT_TRUE(sink->open({pixelFormatFromName("YUYV"), 64, 32, 0, {}, 30}).ok());
    FrameBuffer frame = pattern("YUYV", 0);
    for (int i = 0; i < 5; ++i)
        ASSERT_TRUE(sink->write(frame.view(), {}).ok());
    EXPECT_EQ(sink->writtenFrames(), 3u);
    EXPECT_EQ(sink->droppedFrames(), 2u);
}

TEST_F(Output, VanishedDeviceIsDeviceLostAndCloseFreesEverything)
{
    ASSERT_TRUE(sink->open({pixelFormatFromName("YUYV"), 64, 32, 0, {}, 30}).ok());
    FrameBuffer frame = pattern("YUYV", 0);
    device->dqbufErrors = {-ENODEV};
    auto status = sink->write(frame.view(), {});
    ASSERT_FALSE(status.ok());
    EXPECT_EQ(status.error().code, ErrorCode::DeviceLost);
    ASSERT_TRUE(sink->close().ok());
    EXPECT_EQ(kernel.mappings(), 0u);
    EXPECT_EQ(kernel.openFds(), 0u);
    EXPECT_FALSE(device->streaming);
}

TEST_F(Output, FrameOfAnotherFormatIsRefused)
{
    ASSERT_TRUE(sink->open({pixelFormatFromName("YUYV"), 64, 32, 0, {}, 30}).ok());
    FrameBuffer frame = pattern("NV12", 0);
    EXPECT_EQ(sink->write(frame.view(), {}).error().code, ErrorCode::InvalidArgument);
}

} // namespace
} // namespace overlayd::test
