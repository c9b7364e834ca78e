// SPDX-License-Identifier: Apache-2.0
// The frame path in steady state allocates nothing: the real stages (the synthetic source drawing the demo's
// checkerboard scene, the demo's overlay, a Pipeline, a null sink and a copying sink) run 300 frames after a
// warm-up while every malloc of this test binary is counted, frame by frame.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <malloc.h>
#include <new>
#include <set>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "config/daemon_config.h"
#include "daemon/pipeline.h"
#include "drivers/source_options.h"
#include "overlay/scene_renderer.h"

// Under AddressSanitizer malloc is the sanitizer's: the counting hook is left out and the tests skip.
#if defined(__SANITIZE_ADDRESS__)
#define OVERLAYD_COUNTING_MALLOC 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(memory_sanitizer) || __has_feature(thread_sanitizer)
#define OVERLAYD_COUNTING_MALLOC 0
#endif
#endif
#ifndef OVERLAYD_COUNTING_MALLOC
#define OVERLAYD_COUNTING_MALLOC 1
#endif

namespace {
std::atomic<bool> counting{false};
std::atomic<size_t> allocations{0};

[[maybe_unused]] void counted()
{
    if (counting.load(std::memory_order_relaxed))
        allocations.fetch_add(1, std::memory_order_relaxed);
}
} // namespace

#if OVERLAYD_COUNTING_MALLOC
// glibc's own entry points, which these replacements forward to (the counting hook of this binary only: every
// allocation in the process, C++'s operator new included, comes through one of them).
extern "C" {
void *__libc_malloc(size_t);
void *__libc_calloc(size_t, size_t);
void *__libc_realloc(void *, size_t);
void *__libc_memalign(size_t, size_t);
void __libc_free(void *);
}

extern "C" {
void *malloc(size_t size)
{
    counted();
    return __libc_malloc(size);
}
void *calloc(size_t count, size_t size)
{
    counted();
    return __libc_calloc(count, size);
}
void *realloc(void *p, size_t size)
{
    counted();
    return __libc_realloc(p, size);
}
void *memalign(size_t alignment, size_t size)
{
    counted();
    return __libc_memalign(alignment, size);
}
void *aligned_alloc(size_t alignment, size_t size)
{
    counted();
    return __libc_memalign(alignment, size);
}
int posix_memalign(void **out, size_t alignment, size_t size)
{
    counted();
    *out = __libc_memalign(alignment, size);
    return *out ? 0 : ENOMEM;
}
void free(void *p)
{
    __libc_free(p);
}
}
#endif

namespace overlayd {
namespace {

constexpr int kWarmUpFrames = 30;
constexpr int kCountedFrames = 300;

struct SteadyPipeline {
    Logger logger{[](std::string_view) {}, true};
    DaemonConfig config;
    std::unique_ptr<FrameSource> source;
    Pipeline pipeline{logger};

    // The demo's scene and source at `width` x `height` without the annotations named in `leaveOut`; `copying`: a
    // raw sink on /dev/null too (queued copies, written by its thread).
    void open(unsigned width, unsigned height, bool copying, const std::vector<std::string> &leaveOut)
    {
        std::vector<ConfigProblem> problems;
        auto loaded = loadConfigFile(OVERLAYD_SOURCE_DIR "/config/examples/demo.toml", problems);
        ASSERT_TRUE(loaded) << loaded.error().message;
        config = std::move(*loaded);
        std::erase_if(config.scene.annotations, [&](const Annotation &a) {
            return std::find(leaveOut.begin(), leaveOut.end(), a.name) != leaveOut.end();
        });
        config.source.width = width;
        config.source.height = height;
        auto camera = config.camera.build(width, height);
        ASSERT_TRUE(camera) << camera.error().message;
        auto made = makeSource(config.source, &*camera);
        ASSERT_TRUE(made) << made.error().message;
        source = std::move(*made);
        auto format = source->start();
        ASSERT_TRUE(format) << format.error().message;
        auto renderer = SceneRenderer::create(config.scene, *camera, *format);
        ASSERT_TRUE(renderer) << renderer.error().message;
        pipeline.setRenderer(std::move(*renderer));
        std::vector<SinkOptions> sinks(1);
        sinks[0].kind = SinkKind::Null;
        if (copying) {
            sinks.emplace_back();
            sinks[1].kind = SinkKind::Raw;
            sinks[1].path = "/dev/null";
        }
        std::vector<std::unique_ptr<SinkWorker>> workers;
        for (const SinkOptions &options : sinks) {
            auto sink = makeSink(options);
            ASSERT_TRUE(sink) << sink.error().message;
            workers.push_back(std::make_unique<SinkWorker>(std::move(*sink), options, logger));
        }
        pipeline.setSinks(std::move(workers));
        ASSERT_TRUE(pipeline.openSinks(*format));
    }

    // Runs `frames` frames; with `perFrame`, the allocations of each frame (counted) and whether its timestamp's
    // second differs from the previous frame's.
    struct Frame {
        size_t allocations = 0;
        bool newSecond = false;
        bool newDigit = false; // the frame number has one more digit: the counter's box is wider
        bool newGlyph = false; // the counter shows a digit where it never showed that digit before
    };
    void run(int frames, std::vector<Frame> *perFrame = nullptr)
    {
        for (int i = 0; i < frames; ++i) {
            auto lease = source->nextFrame();
            ASSERT_TRUE(lease) << lease.error().message;
            const auto second = std::chrono::floor<std::chrono::seconds>(lease->metadata().wallClock);
            const uint64_t number = lease->metadata().sequence;
            const bool newDigit = number >= 10 && std::to_string(number).size() > std::to_string(number - 1).size();
            // The counter's glyphs are blended from stamps kept per glyph and place ("frame N" is left-aligned
            // and its digits share one advance: the place of a digit is its index in the string).
            bool newGlyph = false;
            const std::string counter = std::to_string(number);
            for (size_t k = 0; k < counter.size(); ++k)
                newGlyph |= shownDigits_.insert({k, counter[k]}).second;
            const size_t before = allocations.load();
            counting = perFrame != nullptr;
            pipeline.process(std::move(*lease));
            counting = false;
            if (perFrame)
                perFrame->push_back({allocations.load() - before, second != lastSecond_, newDigit, newGlyph});
            lastSecond_ = second;
        }
    }

private:
    std::chrono::system_clock::time_point lastSecond_{};
    std::set<std::pair<size_t, char>> shownDigits_; // (index in the frame number, digit)
};

size_t sinkFrames(const Pipeline &pipeline)
{
    size_t frames = 0;
    for (const auto &sink : pipeline.sinks())
        frames += sink->allocatedFrames();
    return frames;
}

// Every counted frame of the demo at this size, without the annotations in `leaveOut`. `grown`: how many frames
// the sinks' pools allocated during the counted frames (a queue that had never been that long before: bounded by
// queue_depth + 1 per sink, and the one allocation a copying sink may still make after the warm-up).
std::vector<SteadyPipeline::Frame> countFrames(unsigned width, unsigned height, bool copying,
                                               const std::vector<std::string> &leaveOut, size_t *grown = nullptr)
{
    SteadyPipeline steady;
    std::vector<SteadyPipeline::Frame> frames;
    steady.open(width, height, copying, leaveOut);
    if (::testing::Test::HasFatalFailure())
        return frames;
    steady.run(kWarmUpFrames);
    // Every sink has written once: stdio allocates a FILE's buffer at its first write, on the sink's thread.
    for (const auto &sink : steady.pipeline.sinks())
        for (int wait = 0; wait < 1000 && sink->counters().written == 0; ++wait)
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
    const size_t before = sinkFrames(steady.pipeline);
    steady.run(kCountedFrames, &frames);
    if (grown)
        *grown = sinkFrames(steady.pipeline) - before;
    EXPECT_EQ(steady.pipeline.framesIn(), uint64_t(kWarmUpFrames + kCountedFrames));
    return frames;
}

size_t total(const std::vector<SteadyPipeline::Frame> &frames)
{
    size_t sum = 0;
    for (const auto &frame : frames)
        sum += frame.allocations;
    return sum;
}

// The world layers (grid, axes, labels) are blended from what was rendered at start: nothing is allocated.
TEST(SteadyAllocation, DemoWorldLayersToANullSinkAllocateNothing)
{
    if (!OVERLAYD_COUNTING_MALLOC)
        GTEST_SKIP() << "malloc belongs to the sanitizer in this build";
    const auto frames = countFrames(1280, 720, false, {"timestamp", "frame counter"});
    ASSERT_EQ(frames.size(), size_t(kCountedFrames));
    EXPECT_EQ(total(frames), 0u) << "allocations in " << kCountedFrames << " frames";
}

TEST(SteadyAllocation, DemoWorldLayersToACopyingSinkAllocateNothing)
{
    if (!OVERLAYD_COUNTING_MALLOC)
        GTEST_SKIP() << "malloc belongs to the sanitizer in this build";
    size_t grown = 0;
    const auto frames = countFrames(640, 480, true, {"timestamp", "frame counter"}, &grown);
    ASSERT_EQ(frames.size(), size_t(kCountedFrames));
    // Nothing but the copy slots the queue had not needed before (the sink's thread was late once more than in
    // the warm-up), each allocated once, ever.
    EXPECT_EQ(total(frames), grown) << "allocations in " << kCountedFrames << " frames";
    EXPECT_LE(grown, 5u);
}

// What remains: a token text whose string changed after holding still is rendered into a new small layer (its
// native runs). The timestamp changes once a second (every 30th frame of the synthetic clock); every other frame
// allocates nothing. The frame counter, new on every frame, is drawn straight into the frame from cached glyphs:
// no allocation (before the glyph cache, every frame allocated for it), except when it gains a digit and its
// background box, kept as a layer, is rendered again at the new width, or shows a digit where it never showed that
// digit before (a new glyph stamp: a few dozen in all, then none).
TEST(SteadyAllocation, OnlyAFrameWhoseTimestampChangedAllocates)
{
    if (!OVERLAYD_COUNTING_MALLOC)
        GTEST_SKIP() << "malloc belongs to the sanitizer in this build";
    const auto frames = countFrames(1280, 720, false, {});
    ASSERT_EQ(frames.size(), size_t(kCountedFrames));
    size_t newSeconds = 0, others = 0;
    std::string allocating; // the counted frames that allocated although their text did not change
    for (size_t i = 0; i < frames.size(); ++i) {
        newSeconds += frames[i].newSecond;
        if (!frames[i].newSecond && !frames[i].newDigit && !frames[i].newGlyph && frames[i].allocations) {
            ++others;
            allocating += " " + std::to_string(i);
        }
    }
    EXPECT_EQ(others, 0u) << "frames that allocated:" << allocating;
    EXPECT_GE(newSeconds, size_t(kCountedFrames / 30));
    // New places for digits are rare once the counter has run a while: most frames are none of the above.
    size_t newGlyphs = 0;
    for (const auto &frame : frames)
        newGlyphs += frame.newGlyph;
    EXPECT_LE(newGlyphs, size_t(kCountedFrames / 10));
}

// The hook itself: an allocation while counting is seen (else the tests above could not fail).
TEST(SteadyAllocation, TheCounterSeesAnAllocation)
{
    if (!OVERLAYD_COUNTING_MALLOC)
        GTEST_SKIP() << "malloc belongs to the sanitizer in this build";
    allocations = 0;
    counting = true;
    auto *p = new std::vector<int>(1000);
    counting = false;
    delete p;
    EXPECT_GE(allocations.load(), 2u);
}

} // namespace
} // namespace overlayd
