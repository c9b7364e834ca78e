// SPDX-License-Identifier: Apache-2.0
// MJPEG: libjpeg-turbo decoding against OpenCV's own decoder (+-2 codes), and an MJPEG-only camera end to end.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <turbojpeg.h>

#include "drivers/v4l2/mjpeg_decoder.h"
#include "media/frame_buffer.h"
#include "test_devices.h"

namespace overlayd::test {
namespace {

constexpr int kWidth = 96, kHeight = 64;

// Smooth colours, so that chroma subsampling and upsampling filters agree within a code or two.
cv::Mat testImage()
{
    cv::Mat image(kHeight, kWidth, CV_8UC3);
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x)
            image.at<cv::Vec3b>(y, x) = cv::Vec3b(uchar(60 + x), uchar(80 + 2 * y), uchar(200 - x / 2 - y / 2));
    return image;
}

std::vector<uint8_t> encodeOpenCv(const cv::Mat &image)
{
    std::vector<uint8_t> jpeg;
    cv::imencode(".jpg", image, jpeg, {cv::IMWRITE_JPEG_QUALITY, 95});
    return jpeg;
}

// 4:2:2, as most USB webcams send it (OpenCV 4.6 cannot choose the subsampling).
std::vector<uint8_t> encode422(const cv::Mat &image)
{
    tjhandle handle = tjInitCompress();
    unsigned char *data = nullptr;
    unsigned long size = 0;
    tjCompress2(handle, image.data, image.cols, int(image.step), image.rows, TJPF_BGR, &data, &size, TJSAMP_422, 95, 0);
    std::vector<uint8_t> jpeg(data, data + size);
    tjFree(data);
    tjDestroy(handle);
    return jpeg;
}

// OpenCV's decode, in full-range BT.601 YCrCb (JFIF's own encoding).
cv::Mat referenceYcrcb(const std::vector<uint8_t> &jpeg)
{
    cv::Mat bgr = cv::imdecode(jpeg, cv::IMREAD_COLOR), ycrcb;
    cv::cvtColor(bgr, ycrcb, cv::COLOR_BGR2YCrCb);
    return ycrcb;
}

// Mean of channel c of the reference over a box of luma pixels.
double boxMean(const cv::Mat &ycrcb, int c, int x, int y, int w, int h)
{
    double sum = 0;
    for (int j = y; j < y + h; ++j)
        for (int i = x; i < x + w; ++i)
            sum += ycrcb.at<cv::Vec3b>(j, i)[c];
    return sum / (w * h);
}

// Compares every luma sample and every chroma sample (against the reference averaged over the sample's box).
void expectMatches(const FrameView &frame, const cv::Mat &ycrcb)
{
    const PixelFormatInfo &f = *frame.format;
    const bool packed = f.layout == PixelLayout::PackedYuv422;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            const uint8_t luma = packed
                                     ? frame.planes[0].data[y * frame.planes[0].stride + (x / 2) * 4 + f.yOffset[x % 2]]
                                     : frame.planes[0].data[y * frame.planes[0].stride + x];
            ASSERT_NEAR(luma, ycrcb.at<cv::Vec3b>(y, x)[0], 2) << "Y at " << x << "," << y;
        }
    const int hs = f.hSubSampling, vs = f.vSubSampling;
    for (int cy = 0; cy < kHeight / vs; ++cy)
        for (int cx = 0; cx < kWidth / hs; ++cx) {
            const PlaneView &cbPlane = frame.planes[f.cbPlane], &crPlane = frame.planes[f.crPlane];
            const size_t cbAt = cy * cbPlane.stride + (packed ? cx * 4 + f.cbOffset : cx);
            const size_t crAt = cy * crPlane.stride + (packed ? cx * 4 + f.crOffset : cx);
            ASSERT_NEAR(cbPlane.data[cbAt], boxMean(ycrcb, 2, cx * hs, cy * vs, hs, vs), 2) << cx << "," << cy;
            ASSERT_NEAR(crPlane.data[crAt], boxMean(ycrcb, 1, cx * hs, cy * vs, hs, vs), 2) << cx << "," << cy;
        }
}

FrameBuffer decodeInto(const std::vector<uint8_t> &jpeg, const char *format)
{
    auto decoder = makeMjpegDecoder();
    EXPECT_TRUE(decoder.ok()) << decoder.error().message;
    auto buffer = FrameBuffer::allocate({pixelFormatFromName(format), kWidth, kHeight, 0, {}, 0.0});
    EXPECT_TRUE(buffer.ok());
    auto status = (*decoder)->decode(jpeg, buffer->view());
    EXPECT_TRUE(status.ok()) << status.error().message;
    return std::move(buffer.value());
}

TEST(V4l2Mjpeg, Decodes420ToI420LikeOpenCv)
{
    const auto jpeg = encodeOpenCv(testImage());
    FrameBuffer frame = decodeInto(jpeg, "YUV420");
    expectMatches(frame.view(), referenceYcrcb(jpeg));
}

TEST(V4l2Mjpeg, Decodes420ToYuyvLikeOpenCv)
{
    const auto jpeg = encodeOpenCv(testImage());
    FrameBuffer frame = decodeInto(jpeg, "YUYV");
    expectMatches(frame.view(), referenceYcrcb(jpeg));
}

TEST(V4l2Mjpeg, Decodes422ToBothOutputsLikeOpenCv)
{
    const auto jpeg = encode422(testImage());
    FrameBuffer i420 = decodeInto(jpeg, "YUV420");
    expectMatches(i420.view(), referenceYcrcb(jpeg));
    FrameBuffer yuyv = decodeInto(jpeg, "YUYV");
    expectMatches(yuyv.view(), referenceYcrcb(jpeg));
}

TEST(V4l2Mjpeg, GarbageAndWrongSizeAreMalformed)
{
    auto decoder = makeMjpegDecoder();
    ASSERT_TRUE(decoder.ok());
    auto buffer = FrameBuffer::allocate({pixelFormatFromName("YUV420"), kWidth, kHeight, 0, {}, 0.0});
    const std::vector<uint8_t> garbage(1000, 0x5a);
    EXPECT_EQ((*decoder)->decode(garbage, buffer->view()).error().code, ErrorCode::Malformed);
    cv::Mat small;
    cv::resize(testImage(), small, cv::Size(kWidth / 2, kHeight / 2));
    EXPECT_EQ((*decoder)->decode(encodeOpenCv(small), buffer->view()).error().code, ErrorCode::Malformed);
}

TEST(V4l2Mjpeg, MjpegOnlyCameraDeliversDecodedFullRangeFrames)
{
    CaptureRig rig;
    FakeDevice &device = rig.kernel.add("/dev/video0");
    device.formats = {{V4L2_PIX_FMT_MJPEG, {{kWidth, kHeight}}, {30.0}}};
    rig.make(captureOptions("NV12", kWidth, kHeight, 30.0));
    auto format = rig.source->start();
    ASSERT_TRUE(format.ok()) << format.error().message;
    EXPECT_EQ(format->format->name, "YUV420");
    EXPECT_EQ(format->colorimetry, (Colorimetry{YcbcrMatrix::Bt601, ColourRange::Full}));
    ASSERT_EQ(rig.log.size(), 1u);
    EXPECT_EQ(rig.log[0], "/dev/video0 (Fake Cam): asked 96x64@30 NV12, got 96x64@30 YUV420 (decoded from MJPG)");

    const auto jpeg = encodeOpenCv(testImage());
    ASSERT_TRUE(device.produce(0, std::chrono::microseconds(0), [&](FakeDevice::Buffer &b) {
        std::copy(jpeg.begin(), jpeg.end(), b.planes[0].begin());
        b.bytesUsed[0] = uint32_t(jpeg.size());
    }));
    auto lease = rig.source->nextFrame();
    ASSERT_TRUE(lease.ok()) << lease.error().message;
    expectMatches(lease->view(), referenceYcrcb(jpeg));
    EXPECT_EQ(lease->metadata().colorimetry.range, ColourRange::Full);
    EXPECT_EQ(device.queued.size(), 3u);
    lease->reset();
    EXPECT_EQ(device.queued.size(), 4u);

    ASSERT_TRUE(device.produce(1, std::chrono::microseconds(0), [](FakeDevice::Buffer &b) { b.bytesUsed[0] = 500; }));
    auto broken = rig.source->nextFrame();
    ASSERT_FALSE(broken.ok());
    EXPECT_EQ(broken.error().code, ErrorCode::TryAgain); // a skipped frame, not the end of the stream
    EXPECT_NE(broken.error().message.find("frame 1"), std::string::npos);
    EXPECT_EQ(device.queued.size(), 4u); // the undecodable buffer went straight back
    EXPECT_EQ(rig.source->droppedFrames(), 1u);
    ASSERT_TRUE(device.produce(2, std::chrono::microseconds(0), [](FakeDevice::Buffer &b) { b.bytesUsed[0] = 9; }));
    EXPECT_EQ(rig.source->nextFrame().error().code, ErrorCode::TryAgain);
    EXPECT_EQ(rig.source->droppedFrames(), 2u);
    ASSERT_EQ(rig.log.size(), 2u); // the adjustment line and the first broken frame, not the second
    EXPECT_NE(rig.log[1].find("frame 1"), std::string::npos);
}

TEST(V4l2Mjpeg, YuyvRequestDecodesToYuyv)
{
    CaptureRig rig;
    rig.kernel.add("/dev/video0").formats = {{V4L2_PIX_FMT_MJPEG, {{kWidth, kHeight}}, {30.0}}};
    rig.make(captureOptions("YUYV", kWidth, kHeight, 30.0));
    auto format = rig.source->start();
    ASSERT_TRUE(format.ok()) << format.error().message;
    EXPECT_EQ(format->format->name, "YUYV");
}

} // namespace
} // namespace overlayd::test
