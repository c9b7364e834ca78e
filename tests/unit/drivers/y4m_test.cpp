// SPDX-License-Identifier: Apache-2.0
// Y4M: our sink read back by ffprobe/ffmpeg (size, pix_fmt, frame count, colours) and by our replay (same bytes);
// ffmpeg's own files read by our replay; truncated and malformed files give Malformed errors naming the frame.
#include <filesystem>
#include <fstream>
#include <ostream>

#include <gtest/gtest.h>

#include "drivers/files/y4m_header.h"
#include "drivers/sink_options.h"
#include "drivers/source_options.h"
#include "drivers/synthetic/patterns.h"
#include "media/frame.h"
#include "test_util.h"

namespace overlayd {
namespace {

const std::string kData = OVERLAYD_DRIVERS_TEST_DATA;

std::unique_ptr<FrameSource> startedSource(const SourceOptions &o)
{
    auto source = makeSource(o);
    EXPECT_TRUE(source) << (source ? "" : source.error().message);
    if (!source)
        return nullptr;
    auto format = (*source)->start();
    EXPECT_TRUE(format) << (format ? "" : format.error().message);
    return format ? std::move(*source) : nullptr;
}

SourceOptions synthetic(SyntheticPattern pattern, const std::string &format, unsigned w, unsigned h)
{
    SourceOptions o;
    o.pixelFormat = pixelFormatFromName(format);
    o.width = w, o.height = h, o.fps = 25.0;
    o.synthetic.pattern = pattern;
    return o;
}

SourceOptions replay(const std::string &path, const std::string &format = "YUYV")
{
    SourceOptions o;
    o.kind = SourceKind::Replay;
    o.pixelFormat = pixelFormatFromName(format);
    o.replay.path = path;
    return o;
}

// Writes `frames` frames of a synthetic source through a sink; returns their bytes.
std::vector<std::vector<uint8_t>> writeFrames(const SourceOptions &source, SinkKind kind, const std::string &path,
                                              unsigned frames)
{
    auto input = startedSource(source);
    SinkOptions so;
    so.kind = kind, so.path = path;
    auto sink = makeSink(so);
    EXPECT_TRUE(sink);
    std::vector<std::vector<uint8_t>> written;
    if (!input || !sink)
        return written;
    auto format = input->start();
    EXPECT_TRUE((*sink)->open(*format));
    for (unsigned i = 0; i < frames; ++i) {
        auto lease = input->nextFrame();
        EXPECT_TRUE(lease);
        EXPECT_TRUE((*sink)->write(lease->view(), lease->metadata()));
        written.push_back(test::visibleBytes(lease->view()));
    }
    EXPECT_TRUE((*sink)->close());
    return written;
}

std::vector<std::vector<uint8_t>> readAll(const SourceOptions &o, unsigned limit = 100)
{
    std::vector<std::vector<uint8_t>> frames;
    auto source = startedSource(o);
    while (source && frames.size() < limit) {
        auto lease = source->nextFrame();
        if (!lease) {
            EXPECT_EQ(lease.error().code, ErrorCode::EndOfStream) << lease.error().message;
            break;
        }
        frames.push_back(test::visibleBytes(lease->view()));
    }
    return frames;
}

struct ProbeCase {
    const char *format;
    const char *pixFmt; // what ffprobe must report
};

void PrintTo(const ProbeCase &c, std::ostream *os)
{
    *os << c.format << " -> " << c.pixFmt;
}

class Y4mProbe : public testing::TestWithParam<ProbeCase>
{};

TEST_P(Y4mProbe, FfprobeAgreesOnSizeFormatAndCount)
{
    test::TempDir dir;
    const std::string path = dir.path("out.y4m");
    writeFrames(synthetic(SyntheticPattern::ColourBars, GetParam().format, 64, 48), SinkKind::Y4m, path, 3);
    int status = -1;
    const std::string probe = test::runCommand("/usr/bin/ffprobe -v error -count_frames -select_streams v:0 "
                                               "-show_entries stream=width,height,pix_fmt,r_frame_rate,nb_read_frames "
                                               "-of default=noprint_wrappers=1 '" +
                                                   path + "'",
                                               &status);
    ASSERT_EQ(status, 0) << probe;
    EXPECT_NE(probe.find("width=64\n"), std::string::npos) << probe;
    EXPECT_NE(probe.find("height=48\n"), std::string::npos) << probe;
    EXPECT_NE(probe.find("pix_fmt=" + std::string(GetParam().pixFmt) + "\n"), std::string::npos) << probe;
    EXPECT_NE(probe.find("nb_read_frames=3\n"), std::string::npos) << probe;
    EXPECT_NE(probe.find("r_frame_rate=25/1\n"), std::string::npos) << probe;

    // ffmpeg decodes the bars back to their colours (its BT.601 limited-range converter, +-4 codes).
    if (std::string(GetParam().pixFmt) == "gray")
        return;
    const std::string rgb =
        test::runCommand("/usr/bin/ffmpeg -v error -i '" + path + "' -frames:v 1 -f rawvideo -pix_fmt rgb24 -");
    ASSERT_EQ(rgb.size(), 64u * 48 * 3);
    for (unsigned bar = 0; bar < 8; ++bar) {
        const size_t at = (size_t(24) * 64 + bar * 8 + 4) * 3;
        for (unsigned k = 0; k < 3; ++k)
            EXPECT_NEAR(uint8_t(rgb[at + k]), kBarColours[bar][k], 4) << "bar " << bar;
    }
}

INSTANTIATE_TEST_SUITE_P(Formats, Y4mProbe,
                         testing::Values(ProbeCase{"YUV420", "yuv420p"}, ProbeCase{"YVU420", "yuv420p"},
                                         ProbeCase{"NV12", "yuv420p"}, ProbeCase{"NV21", "yuv420p"},
                                         ProbeCase{"YUYV", "yuv422p"}, ProbeCase{"UYVY", "yuv422p"},
                                         ProbeCase{"NV16", "yuv422p"}, ProbeCase{"GREY", "gray"},
                                         ProbeCase{"RGB24", "yuv444p"}, ProbeCase{"BGRA32", "yuv444p"}),
                         [](const auto &test) { return std::string(test.param.format); });

TEST(Y4mHeader, FrameRatesAreExactRatios)
{
    const auto ratio = [](double fps) {
        unsigned num = 0, den = 0;
        fpsToRatio(fps, num, den);
        return std::to_string(num) + ":" + std::to_string(den);
    };
    EXPECT_EQ(ratio(30.0), "30:1");
    EXPECT_EQ(ratio(30000.0 / 1001.0), "30000:1001");
    EXPECT_EQ(ratio(12.5), "25:2");
    EXPECT_EQ(ratio(0.0), "30:1");
}

TEST(Y4mReplay, ReadsBackTheBytesWeWrote)
{
    for (const char *format : {"YUV420", "YUYV", "GREY"}) {
        SCOPED_TRACE(format);
        test::TempDir dir;
        const std::string path = dir.path("noise.y4m");
        const auto written = writeFrames(synthetic(SyntheticPattern::Noise, format, 38, 22), SinkKind::Y4m, path, 3);
        EXPECT_EQ(readAll(replay(path)), written);
    }
}

// NV12 is written as I420 planes and replays as YUV420: the same samples, deinterleaved.
TEST(Y4mReplay, Nv12ComesBackAsI420)
{
    test::TempDir dir;
    const std::string path = dir.path("nv12.y4m");
    const auto written = writeFrames(synthetic(SyntheticPattern::Noise, "NV12", 16, 8), SinkKind::Y4m, path, 1);
    const auto read = readAll(replay(path));
    ASSERT_EQ(read.size(), 1u);
    const std::vector<uint8_t> &nv12 = written[0], &i420 = read[0];
    ASSERT_EQ(i420.size(), nv12.size());
    EXPECT_TRUE(std::equal(nv12.begin(), nv12.begin() + 128, i420.begin()));
    for (size_t c = 0; c < 32; ++c) {
        EXPECT_EQ(i420[128 + c], nv12[128 + 2 * c]);     // Cb
        EXPECT_EQ(i420[160 + c], nv12[128 + 2 * c + 1]); // Cr
    }
}

TEST(Y4mReplay, FfmpegFilesMatchFfmpegsOwnUnpacking)
{
    struct Case {
        const char *y4m, *reference;
    };
    for (const Case c : {Case{"ffmpeg_420.y4m", "ffmpeg_420.i420"}, Case{"ffmpeg_422.y4m", "ffmpeg_422.yuyv"},
                         Case{"ffmpeg_mono.y4m", "ffmpeg_mono.grey"}}) {
        SCOPED_TRACE(c.y4m);
        const auto frames = readAll(replay(kData + "/" + c.y4m));
        const std::vector<uint8_t> reference = test::readFile(kData + "/" + c.reference);
        ASSERT_EQ(frames.size(), 3u);
        std::vector<uint8_t> all;
        for (const auto &frame : frames)
            all.insert(all.end(), frame.begin(), frame.end());
        EXPECT_EQ(all, reference);
    }
}

// 4:4:4 has no table format: it is converted to the configured one. Through RGB24 it must match ffmpeg's own
// BT.601 limited-range decoding within a few codes.
TEST(Y4mReplay, Ffmpeg444ConvertsToTheConfiguredFormat)
{
    const auto frames = readAll(replay(kData + "/ffmpeg_444.y4m", "RGB24"));
    const std::vector<uint8_t> reference = test::readFile(kData + "/ffmpeg_444.rgb");
    ASSERT_EQ(frames.size(), 3u);
    ASSERT_EQ(reference.size(), 3 * frames[0].size());
    int worst = 0;
    for (size_t f = 0; f < 3; ++f) {
        for (size_t i = 0; i < frames[f].size(); ++i)
            worst = std::max(worst, std::abs(int(frames[f][i]) - int(reference[f * frames[f].size() + i])));
    }
    EXPECT_LE(worst, 3);
}

TEST(Y4mReplay, LoopsAndKeepsCounting)
{
    SourceOptions o = replay(kData + "/ffmpeg_420.y4m");
    o.replay.loop = true;
    auto source = startedSource(o);
    ASSERT_TRUE(source);
    std::vector<uint64_t> hashes;
    std::chrono::system_clock::time_point first{};
    for (uint64_t n = 0; n < 7; ++n) {
        auto lease = source->nextFrame();
        ASSERT_TRUE(lease) << lease.error().message;
        EXPECT_EQ(lease->metadata().sequence, n);
        if (n == 0)
            first = lease->metadata().wallClock;
        EXPECT_EQ(lease->metadata().wallClock - first, std::chrono::milliseconds(200 * n)); // F5:1
        hashes.push_back(test::hashFrame(lease->view()));
    }
    EXPECT_EQ(hashes[3], hashes[0]);
    EXPECT_EQ(hashes[6], hashes[0]);
    EXPECT_EQ(hashes[5], hashes[2]);
    EXPECT_NE(hashes[2], hashes[0]); // testsrc2's first two frames are the same at this size
}

std::string writeText(const test::TempDir &dir, const std::string &name, const std::string &bytes)
{
    const std::string path = dir.path(name);
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
}

Error firstError(const SourceOptions &o, unsigned *goodFrames)
{
    auto source = makeSource(o);
    if (!source)
        return source.error();
    if (auto format = (*source)->start(); !format)
        return format.error();
    for (*goodFrames = 0;; ++*goodFrames) {
        auto lease = (*source)->nextFrame();
        if (!lease)
            return lease.error();
    }
}

TEST(Y4mReplay, TruncatedFileNamesFileAndFrame)
{
    test::TempDir dir;
    const std::string path = dir.path("cut.y4m");
    writeFrames(synthetic(SyntheticPattern::Noise, "YUV420", 16, 8), SinkKind::Y4m, path, 3);
    std::vector<uint8_t> bytes = test::readFile(path);
    bytes.resize(bytes.size() - 100); // frame 2 loses 100 of its 192 bytes
    const std::string cut = writeText(dir, "cut2.y4m", std::string(bytes.begin(), bytes.end()));
    unsigned good = 0;
    const Error error = firstError(replay(cut), &good);
    EXPECT_EQ(good, 2u);
    EXPECT_EQ(error.code, ErrorCode::Malformed);
    EXPECT_NE(error.message.find(cut), std::string::npos) << error.message;
    EXPECT_NE(error.message.find("frame 2"), std::string::npos) << error.message;
}

TEST(Y4mReplay, MalformedFilesAreErrorsNotCrashes)
{
    test::TempDir dir;
    const std::string frame(16 * 8 * 3 / 2, 'x');
    struct Case {
        std::string bytes;
        ErrorCode code;
        const char *mentions;
    };
    const Case cases[] = {
        {"", ErrorCode::Malformed, "header"},
        {"NOTY4M W16 H8\n", ErrorCode::Malformed, "YUV4MPEG2"},
        {"YUV4MPEG2 W16 H8", ErrorCode::Malformed, "header"},
        {"YUV4MPEG2 W0 H8\n", ErrorCode::Malformed, "width"},
        {"YUV4MPEG2 Wabc H8\n", ErrorCode::Malformed, "width"},
        {"YUV4MPEG2 W100000 H8\n", ErrorCode::Malformed, "exceeds"},
        // 16384 x 16384 x 3 bytes = 768 MiB a frame: within the per-side limit, over kMaxFrameBytes.
        {"YUV4MPEG2 W16384 H16384 C444\nFRAME\n", ErrorCode::Malformed, "805306368 bytes a frame, over the limit"},
        {"YUV4MPEG2 W16384 H16384 C420jpeg\nFRAME\n", ErrorCode::Malformed, "402653184 bytes a frame"},
        {"YUV4MPEG2 W16 H8 F0:1\n", ErrorCode::Malformed, "frame rate"},
        {"YUV4MPEG2 W16 H8 C411\n", ErrorCode::Unsupported, "C411"},
        {"YUV4MPEG2 W16 H8 C420p10\n", ErrorCode::Unsupported, "C420p10"},
        {"YUV4MPEG2 W16 H8\nFRAME\n" + frame + "GARBAGE\n" + frame, ErrorCode::Malformed, "frame 1"},
        {"YUV4MPEG2 W16 H8\nFRAME\n" + frame + "FRA", ErrorCode::Malformed, "frame 1"},
        {"YUV4MPEG2 W16 H8\nFRAME" + std::string(10000, ' '), ErrorCode::Malformed, "frame 0"},
    };
    int n = 0;
    for (const Case &c : cases) {
        const std::string path = writeText(dir, "bad" + std::to_string(n++) + ".y4m", c.bytes);
        SCOPED_TRACE(c.bytes.substr(0, 40));
        unsigned good = 0;
        const Error error = firstError(replay(path), &good);
        EXPECT_EQ(error.code, c.code) << error.message;
        EXPECT_NE(error.message.find(c.mentions), std::string::npos) << error.message;
        EXPECT_NE(error.message.find(path), std::string::npos) << error.message;
    }
}

TEST(Y4mReplay, MissingFileIsNotFound)
{
    unsigned good = 0;
    EXPECT_EQ(firstError(replay("/nonexistent/in.y4m"), &good).code, ErrorCode::NotFound);
}

// Largest frames under the limit still parse: 16384 x 10922 at 4:2:0 is 255.99 MiB.
TEST(Y4mHeader, AFrameJustUnderTheByteLimitIsAccepted)
{
    auto header = parseY4mHeader("YUV4MPEG2 W16384 H10922 C420jpeg", "big.y4m");
    ASSERT_TRUE(header.ok()) << header.error().message;
    EXPECT_LE(header->frameBytes(), kMaxFrameBytes);
    EXPECT_FALSE(parseY4mHeader("YUV4MPEG2 W16384 H10924 C420jpeg", "big.y4m").ok());
}

// A directory opens with fopen() and fails only at the first read ("header missing"): named for what it is.
TEST(Y4mReplay, ADirectoryIsNotAFile)
{
    test::TempDir dir;
    const std::string path = dir.path("folder.y4m");
    ASSERT_TRUE(std::filesystem::create_directory(path));
    unsigned good = 0;
    const Error error = firstError(replay(path), &good);
    EXPECT_EQ(error.message, path + ": is a directory, not a regular file");
}

} // namespace
} // namespace overlayd
