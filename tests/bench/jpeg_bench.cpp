// SPDX-License-Identifier: Apache-2.0
// jpeg_bench: JpegEncoder compressing 1920x1080 frames from their own planes, against the RGB round trip it
// replaces (frameToRgb, then tjCompress2 from RGB), in the same run.
//
// Usage: jpeg_bench [--quality=N] [Google Benchmark flags]; quality 80 (the HTTP stream's default) unless given.
// Both paths get the same help: one persistent libjpeg-turbo handle, a preallocated output buffer, and the same
// chroma subsampling (4:2:2 for YUYV, 4:2:0 for NV12), so the ratio measures what happens before the DCT. Before any
// timing, each frame's two JPEGs are decoded and compared (mean |difference| per channel <= 2 levels); a mismatch
// aborts the run, so a fast wrong answer is never reported. Cases are named BM_Jpeg/<path>/<format>/<size>/<colours>
// (path: native, native_planes_only, rgb_round_trip). At the end a "ratio" line per case gives both costs per
// frame, wall clock and CPU time (the steadier figure on a shared machine; the median of --benchmark_repetitions),
// and the speed-up.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <turbojpeg.h>

#include "media/convert/frame_convert.h"
#include "media/frame_buffer.h"
#include "media/jpeg/jfif_planes.h"
#include "media/jpeg/jpeg_encoder.h"
#include "tests/bench_support/same_run.h"

namespace {

using namespace overlayd;

constexpr unsigned kWidth = 1920, kHeight = 1080;
constexpr double kMaxMeanDifference = 2.0;

struct Case {
    const char *name; // benchmark suffix
    const char *format;
    Colorimetry colorimetry;
    int subsampling; // the native path's, given to the round trip too
};

const Case kCases[] = {
    {"YUYV/1920x1080/bt601-limited", "YUYV", {YcbcrMatrix::Bt601, ColourRange::Limited}, TJSAMP_422},
    {"NV12/1920x1080/bt601-limited", "NV12", {YcbcrMatrix::Bt601, ColourRange::Limited}, TJSAMP_420},
    {"YUYV/1920x1080/bt709-limited", "YUYV", {YcbcrMatrix::Bt709, ColourRange::Limited}, TJSAMP_422},
};

struct TjDeleter {
    void operator()(void *handle) const { tjDestroy(handle); }
};
using TjHandle = std::unique_ptr<void, TjDeleter>;

[[noreturn]] void fail(const std::string &message)
{
    std::fprintf(stderr, "jpeg_bench: %s\n", message.c_str());
    std::exit(EXIT_FAILURE);
}

// Smooth colour waves with sensor-like noise: a camera frame's entropy rather than a flat test card's.
RgbImage scene()
{
    RgbImage image = RgbImage::allocate(kWidth, kHeight);
    std::mt19937 random(7);
    std::uniform_int_distribution<int> noise(-6, 6);
    for (unsigned y = 0; y < kHeight; ++y) {
        uint8_t *px = image.row(y);
        for (unsigned x = 0; x < kWidth; ++x, px += 3) {
            const double waves[3] = {std::sin(x / 97.0 + y / 151.0), std::sin(x / 61.0 - y / 89.0 + 1.0),
                                     std::cos((x + y) / 133.0)};
            for (int c = 0; c < 3; ++c)
                px[c] = uint8_t(std::clamp(int(128 + 100 * waves[c]) + noise(random), 0, 255));
        }
    }
    return image;
}

struct Fixture {
    const Case *spec = nullptr;
    std::unique_ptr<FrameBuffer> frame;
    std::unique_ptr<JpegEncoder> encoder;
    std::vector<uint8_t> native;
    TjHandle compressor;
    std::vector<uint8_t> roundTrip; // tjBufSize() bytes
    unsigned long roundTripSize = 0;
    int quality = 80;

    void encodeNative()
    {
        if (!encoder->encode(frame->view(), spec->colorimetry, quality, native))
            fail(std::string(spec->name) + ": the encoder failed");
    }
    void encodeRoundTrip()
    {
        auto rgb = frameToRgb(frame->view(), spec->colorimetry);
        unsigned char *buffer = roundTrip.data();
        roundTripSize = roundTrip.size();
        if (!rgb || tjCompress2(compressor.get(), rgb->rgb.data(), int(kWidth), 0, int(kHeight), TJPF_RGB, &buffer,
                                &roundTripSize, spec->subsampling, quality, TJFLAG_NOREALLOC) != 0)
            fail(std::string(spec->name) + ": the RGB round trip failed");
    }
};

std::map<std::string, Fixture> fixtures;

std::vector<uint8_t> decode(const uint8_t *jpeg, size_t size)
{
    TjHandle handle(tjInitDecompress());
    std::vector<uint8_t> rgb(size_t(kWidth) * kHeight * 3);
    if (tjDecompress2(handle.get(), jpeg, size, rgb.data(), int(kWidth), 0, int(kHeight), TJPF_RGB, 0) != 0)
        fail("a JPEG does not decode");
    return rgb;
}

void setUp(const Case &spec, int quality)
{
    Fixture &f = fixtures[spec.name];
    f.spec = &spec;
    f.quality = quality;
    auto frame = FrameBuffer::allocate({pixelFormatFromName(spec.format), kWidth, kHeight, 0, spec.colorimetry, 30.0});
    auto encoder = JpegEncoder::create();
    if (!frame || !encoder || !rgbToFrame(scene(), spec.colorimetry, frame->view()))
        fail(std::string(spec.name) + ": cannot set up");
    f.frame = std::make_unique<FrameBuffer>(std::move(*frame));
    f.encoder = std::make_unique<JpegEncoder>(std::move(*encoder));
    f.compressor.reset(tjInitCompress());
    f.roundTrip.resize(tjBufSize(int(kWidth), int(kHeight), spec.subsampling));

    f.encodeNative();
    f.encodeRoundTrip();
    const std::vector<uint8_t> a = decode(f.native.data(), f.native.size());
    const std::vector<uint8_t> b = decode(f.roundTrip.data(), f.roundTripSize);
    double sums[3] = {0, 0, 0};
    for (size_t i = 0; i < a.size(); ++i)
        sums[i % 3] += std::abs(int(a[i]) - int(b[i]));
    const double pixels = double(kWidth) * kHeight;
    const double worst = std::max({sums[0], sums[1], sums[2]}) / pixels;
    if (!(worst <= kMaxMeanDifference))
        fail(std::string(spec.name) + ": native and round-trip JPEGs differ by a mean of " + std::to_string(worst) +
             " levels; not timing a wrong answer");
    // stderr: stdout carries the JSON under --benchmark_format=json.
    std::fprintf(stderr, "verified %s: mean |native - round trip| R %.2f G %.2f B %.2f; %zu vs %lu bytes\n", spec.name,
                 sums[0] / pixels, sums[1] / pixels, sums[2] / pixels, f.native.size(), f.roundTripSize);
}

void setCounters(benchmark::State &state)
{
    state.SetItemsProcessed(state.iterations());
    state.counters["fps"] = benchmark::Counter(1.0, benchmark::Counter::kIsIterationInvariantRate);
}

void benchNative(benchmark::State &state, const std::string &name)
{
    Fixture &f = fixtures.at(name);
    for (auto _ : state) {
        f.encodeNative();
        benchmark::DoNotOptimize(f.native.data());
    }
    setCounters(state);
}

// The native path's own work before libjpeg-turbo: de-interleaving and colour mapping into JfifPlanes.
void benchGather(benchmark::State &state, const std::string &name)
{
    Fixture &f = fixtures.at(name);
    const JfifMapping mapping(f.spec->colorimetry);
    JfifPlanes planes;
    for (auto _ : state) {
        if (!planes.gather(f.frame->view(), mapping))
            fail(name + ": gather failed");
        benchmark::DoNotOptimize(planes.data());
        benchmark::ClobberMemory();
    }
    setCounters(state);
}

void benchRoundTrip(benchmark::State &state, const std::string &name)
{
    Fixture &f = fixtures.at(name);
    for (auto _ : state) {
        f.encodeRoundTrip();
        benchmark::DoNotOptimize(f.roundTrip.data());
    }
    setCounters(state);
}

} // namespace

int main(int argc, char **argv)
{
    int quality = 80;
    // Take --quality=N out of argv before Google Benchmark sees (and rejects) it.
    int kept = 1;
    for (int i = 1; i < argc; ++i) {
        if (std::strncmp(argv[i], "--quality=", 10) == 0)
            quality = std::atoi(argv[i] + 10);
        else
            argv[kept++] = argv[i];
    }
    argc = kept;
    if (quality < 1 || quality > 100)
        fail("--quality must be in 1..100");

    if (!bench::initialize(argc, argv))
        return EXIT_FAILURE;

    for (const Case &spec : kCases) {
        setUp(spec, quality);
        const std::string name = spec.name;
        benchmark::RegisterBenchmark(("BM_Jpeg/native/" + name).c_str(), benchNative, name)
            ->Unit(benchmark::kMillisecond);
        benchmark::RegisterBenchmark(("BM_Jpeg/native_planes_only/" + name).c_str(), benchGather, name)
            ->Unit(benchmark::kMillisecond);
        benchmark::RegisterBenchmark(("BM_Jpeg/rgb_round_trip/" + name).c_str(), benchRoundTrip, name)
            ->Unit(benchmark::kMillisecond);
    }

    const auto reporter = bench::runAll();
    for (const Case &spec : kCases) {
        const std::string native = std::string("BM_Jpeg/native/") + spec.name,
                          rgb = std::string("BM_Jpeg/rgb_round_trip/") + spec.name;
        const auto nativeWall = reporter->wallSeconds(native), rgbWall = reporter->wallSeconds(rgb);
        const auto nativeCpu = reporter->cpuSeconds(native), rgbCpu = reporter->cpuSeconds(rgb);
        if (!nativeWall || !rgbWall || !nativeCpu || !rgbCpu)
            continue; // filtered out by --benchmark_filter
        std::fprintf(reporter->ratioStream(),
                     "ratio %s q%d: wall native %.2f / round trip %.2f ms/frame = %.2fx; cpu native %.2f / round trip "
                     "%.2f ms/frame = %.2fx\n",
                     spec.name, quality, *nativeWall * 1e3, *rgbWall * 1e3, *rgbWall / *nativeWall, *nativeCpu * 1e3,
                     *rgbCpu * 1e3, *rgbCpu / *nativeCpu);
    }
    return EXIT_SUCCESS;
}
