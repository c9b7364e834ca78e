// SPDX-License-Identifier: Apache-2.0
// Raw frames, PNG/JPEG snapshots, image-sequence replay and the null sink.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "drivers/sink_options.h"
#include "drivers/source_options.h"
#include "drivers/synthetic/patterns.h"
#include "media/convert/frame_convert.h"
#include "test_util.h"

namespace overlayd {
namespace {

namespace fs = std::filesystem;

// A padded-stride frame of noise written through a sink, several times with increasing sequence numbers.
void writeThrough(FrameSink &sink, FrameBuffer &frame, unsigned frames)
{
    const FrameLayout &layout = frame.layout();
    ASSERT_TRUE(sink.open({layout.format, layout.width, layout.height, layout.planes[0].stride, {}, 25.0}));
    for (unsigned n = 0; n < frames; ++n) {
        FrameMetadata metadata;
        metadata.sequence = n;
        ASSERT_TRUE(sink.write(frame.view(), metadata));
    }
    ASSERT_TRUE(sink.close());
}

std::unique_ptr<FrameSink> sink(SinkKind kind, const std::string &path, unsigned every = 1)
{
    SinkOptions o;
    o.kind = kind, o.path = path, o.every = every;
    auto made = makeSink(o);
    EXPECT_TRUE(made) << (made ? "" : made.error().message);
    return made ? std::move(*made) : nullptr;
}

SourceOptions rawReplay(const std::string &path, const std::string &format, unsigned w, unsigned h)
{
    SourceOptions o;
    o.kind = SourceKind::Replay;
    o.pixelFormat = pixelFormatFromName(format);
    o.width = w, o.height = h, o.fps = 10.0;
    o.replay.path = path;
    o.replay.format = ReplayFormat::Raw;
    return o;
}

TEST(RawFiles, SinkPacksRowsAndReplayReadsThemBack)
{
    test::TempDir dir;
    const std::string path = dir.path("frames.nv12");
    FrameBuffer frame = test::makeFrame("NV12", 30, 20, 34);
    for (size_t i = 0; i < frame.size(); ++i)
        frame.data()[i] = uint8_t(i * 13 + 1);
    writeThrough(*sink(SinkKind::Raw, path), frame, 3);
    EXPECT_EQ(fs::file_size(path), 3u * 30 * 20 * 3 / 2); // rows packed: no stride padding in the file

    auto source = makeSource(rawReplay(path, "NV12", 30, 20));
    ASSERT_TRUE(source);
    ASSERT_TRUE((*source)->start());
    for (int n = 0; n < 3; ++n) {
        auto lease = (*source)->nextFrame();
        ASSERT_TRUE(lease);
        EXPECT_EQ(test::visibleBytes(lease->view()), test::visibleBytes(frame.view()));
    }
    auto end = (*source)->nextFrame();
    ASSERT_FALSE(end);
    EXPECT_EQ(end.error().code, ErrorCode::EndOfStream);
}

TEST(RawFiles, TruncatedFrameIsMalformedNamingIt)
{
    test::TempDir dir;
    const std::string path = dir.path("cut.yuyv");
    std::ofstream(path, std::ios::binary) << std::string(2 * 8 * 4 * 2 + 10, 'y'); // 2 frames of 8x4 YUYV + 10
    auto source = makeSource(rawReplay(path, "YUYV", 8, 4));
    ASSERT_TRUE(source);
    ASSERT_TRUE((*source)->start());
    EXPECT_TRUE((*source)->nextFrame());
    EXPECT_TRUE((*source)->nextFrame());
    auto third = (*source)->nextFrame();
    ASSERT_FALSE(third);
    EXPECT_EQ(third.error().code, ErrorCode::Malformed);
    EXPECT_NE(third.error().message.find(path + ": frame 2"), std::string::npos) << third.error().message;
}

TEST(Snapshots, EveryNthFrameNumberedBySequence)
{
    test::TempDir dir;
    FrameBuffer frame = test::makeFrame("YUYV", 64, 16, 8);
    ASSERT_TRUE(rgbToFrame(colourBars(64, 16), {}, frame.view()));
    writeThrough(*sink(SinkKind::Snapshot, dir.path("snap_%03d.png"), 2), frame, 5);
    EXPECT_TRUE(fs::exists(dir.path("snap_000.png")));
    EXPECT_FALSE(fs::exists(dir.path("snap_001.png")));
    EXPECT_TRUE(fs::exists(dir.path("snap_002.png")));
    EXPECT_TRUE(fs::exists(dir.path("snap_004.png")));
    EXPECT_FALSE(fs::exists(dir.path("snap_005.png")));
    const cv::Mat png = cv::imread(dir.path("snap_002.png"), cv::IMREAD_COLOR);
    ASSERT_EQ(png.cols, 64);
    for (unsigned bar = 0; bar < 8; ++bar) {
        const cv::Vec3b bgr = png.at<cv::Vec3b>(8, int(bar * 8 + 4));
        EXPECT_NEAR(bgr[2], kBarColours[bar][0], 3);
        EXPECT_NEAR(bgr[1], kBarColours[bar][1], 3);
        EXPECT_NEAR(bgr[0], kBarColours[bar][2], 3);
    }
}

TEST(Snapshots, JpegWithoutNumberIsReplaced)
{
    test::TempDir dir;
    FrameBuffer frame = test::makeFrame("NV12", 32, 16);
    ASSERT_TRUE(fillFrame(frame.view(), {}, 200, 40, 40));
    writeThrough(*sink(SinkKind::Snapshot, dir.path("live.jpg")), frame, 3);
    const cv::Mat jpg = cv::imread(dir.path("live.jpg"), cv::IMREAD_COLOR);
    ASSERT_FALSE(jpg.empty());
    EXPECT_NEAR(jpg.at<cv::Vec3b>(8, 16)[2], 200, 6);
    EXPECT_EQ(std::distance(fs::directory_iterator(dir.path("")), fs::directory_iterator()), 1); // no temp left
}

// A link planted where an older snapshot writer put its temporary ("live.jpg.tmp") neither redirects the snapshot
// nor breaks it: the link's target keeps its bytes and the snapshot still lands.
TEST(Snapshots, APlantedTemporaryLinkIsNotFollowed)
{
    test::TempDir dir;
    std::ofstream(dir.path("victim.txt")) << "keep me";
    fs::create_symlink(dir.path("victim.txt"), dir.path("live.jpg.tmp"));
    FrameBuffer frame = test::makeFrame("NV12", 32, 16);
    ASSERT_TRUE(fillFrame(frame.view(), {}, 200, 40, 40));
    writeThrough(*sink(SinkKind::Snapshot, dir.path("live.jpg")), frame, 2);
    std::ifstream victim(dir.path("victim.txt"));
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(victim), {}), "keep me");
    EXPECT_FALSE(cv::imread(dir.path("live.jpg"), cv::IMREAD_COLOR).empty());
    EXPECT_TRUE(fs::is_symlink(dir.path("live.jpg.tmp")));
}

SourceOptions images(const std::string &pattern, const std::string &format)
{
    SourceOptions o;
    o.kind = SourceKind::Replay;
    o.pixelFormat = pixelFormatFromName(format);
    o.fps = 5.0;
    o.replay.path = pattern;
    o.replay.firstIndex = 1;
    return o;
}

TEST(ImageReplay, PngSequenceInRgbIsExactAndInI420MatchesOpenCv)
{
    test::TempDir dir;
    std::vector<RgbImage> pictures;
    for (int n = 1; n <= 3; ++n) {
        pictures.push_back(test::blockyImage(32, 24, 2, 2, uint32_t(n)));
        cv::Mat bgr;
        cv::cvtColor(test::toMat(pictures.back()), bgr, cv::COLOR_RGB2BGR);
        ASSERT_TRUE(cv::imwrite(dir.path("img" + std::to_string(n) + ".png"), bgr));
    }
    auto rgb = makeSource(images(dir.path("img%d.png"), "RGB24"));
    ASSERT_TRUE(rgb);
    auto format = (*rgb)->start();
    ASSERT_TRUE(format);
    EXPECT_EQ(format->width, 32u);
    for (int n = 0; n < 3; ++n) {
        auto lease = (*rgb)->nextFrame();
        ASSERT_TRUE(lease);
        EXPECT_EQ(test::visibleBytes(lease->view()), pictures[size_t(n)].rgb);
    }
    EXPECT_EQ((*rgb)->nextFrame().error().code, ErrorCode::EndOfStream);

    auto i420 = makeSource(images(dir.path("img%d.png"), "YUV420"));
    ASSERT_TRUE((*i420)->start());
    auto lease = (*i420)->nextFrame();
    ASSERT_TRUE(lease);
    cv::Mat reference;
    cv::cvtColor(test::toMat(pictures[0]), reference, cv::COLOR_RGB2YUV_I420);
    const std::vector<uint8_t> ours = test::visibleBytes(lease->view());
    ASSERT_EQ(ours.size(), reference.total());
    for (size_t i = 0; i < ours.size(); ++i)
        ASSERT_NEAR(ours[i], reference.data[i], 1) << "byte " << i;
}

TEST(ImageReplay, BadSequencesAreClearErrors)
{
    test::TempDir dir;
    unsigned good = 0;
    auto firstError = [&](const SourceOptions &o) -> Error {
        auto source = makeSource(o);
        if (!source)
            return source.error();
        if (auto started = (*source)->start(); !started)
            return started.error();
        for (good = 0;; ++good) {
            auto lease = (*source)->nextFrame();
            if (!lease)
                return lease.error();
        }
    };
    EXPECT_EQ(firstError(images(dir.path("none%d.png"), "YUYV")).code, ErrorCode::NotFound);

    cv::imwrite(dir.path("a1.png"), cv::Mat(8, 8, CV_8UC3, cv::Scalar(1, 2, 3)));
    cv::imwrite(dir.path("a2.png"), cv::Mat(8, 10, CV_8UC3, cv::Scalar(1, 2, 3)));
    Error error = firstError(images(dir.path("a%d.png"), "YUYV"));
    EXPECT_EQ(error.code, ErrorCode::Malformed);
    EXPECT_NE(error.message.find("frame 1"), std::string::npos) << error.message;
    EXPECT_NE(error.message.find("a2.png"), std::string::npos) << error.message;

    cv::imwrite(dir.path("b1.png"), cv::Mat(8, 8, CV_8UC3, cv::Scalar(1, 2, 3)));
    std::ofstream(dir.path("b2.png"), std::ios::binary) << "\x89PNG\r\n\x1a\n not really";
    error = firstError(images(dir.path("b%d.png"), "YUYV"));
    EXPECT_EQ(error.code, ErrorCode::Malformed);
    EXPECT_NE(error.message.find("b2.png"), std::string::npos) << error.message;
    EXPECT_EQ(good, 1u);
}

TEST(NullSink, CountsFrames)
{
    FrameBuffer frame = test::makeFrame("GREY", 4, 4);
    auto null = sink(SinkKind::Null, "");
    writeThrough(*null, frame, 7);
    EXPECT_NE(null->describe().find("7 frames"), std::string::npos) << null->describe();
}

} // namespace
} // namespace overlayd
