// SPDX-License-Identifier: Apache-2.0
// The overlay's Speed section: a ground grid of 40 lines 2 px wide, an axes triad 3 px wide and 3 text labels seen by
// a pitched-down camera, at 1280x720 and 1920x1080 in YUYV and NV12:
//   static       per-frame blend of the unchanged overlay;
//   dynamic      the pose changes every frame: re-project, re-rasterize, convert, blend;
//   opencv_naive native -> BGR (cvtColor), cv::line LINE_AA + cv::putText, BGR -> native (what most users write);
//   memcpy       one frame copy over a ring of frames larger than the caches (cold), the floor.
//   touch        one read and one write of each cache line the cached overlay's runs touch, nothing else: what
//                reaching those lines of a cold frame costs, the floor under `static`.
// and config/examples/reverse_camera.toml's scene (guide lines 4 px wide with three distance marks, seen by a camera
// behind and above the rear axle looking back and down, plus its hint text on a translucent box):
//   steering     the road-wheel angle changes before every blend (setGuideSteering, sweeping -30..30 degrees by
//                0.7 a frame, as a 30 Hz steering input would): drawn straight into the frame;
//   steady       setGuideSteering with the angle it already has before every blend (a no-op): the cached blend.
// Ratios are printed at the end from the same run; targets: static/memcpy <= 0.5, opencv_naive/static >= 25,
// dynamic/memcpy <= 2, steering/memcpy <= 2 (the moving-scene target), steady/memcpy <= 0.5 (the static target);
// static/touch says how far the static blend is from its own floor.
#include <cmath>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "cold_frames.h"
#include "overlay/overlay_renderer.h"
#include "overlay/scene_renderer.h"

namespace overlayd {
namespace {

using bench::memcpyBench;
using bench::Ring;

Camera benchCamera(unsigned width, unsigned height, double yawDeg)
{
    const PinholeIntrinsics k{0.8 * width, 0.8 * width, (width - 1) / 2.0, (height - 1) / 2.0,
                              0.0,         int(width),  int(height)};
    const auto projection = Projection::pinhole(k, 0.1, 200.0, DepthRange::MinusOneToOne);
    const auto pose = poseFromYawPitchRoll({-6.0, 0.0, 2.5}, yawDeg, 22.0, 0.0);
    const auto viewport = Viewport::create(ViewportSpec{int(width), int(height)});
    return *Camera::create(*pose, *projection, Distortion{}, *viewport);
}

Annotation item(const std::string &name, Shape shape, Rgba colour, double width)
{
    Annotation a{name, SceneGraph::kWorld, Style{}, std::move(shape)};
    a.style.colour = colour;
    a.style.width = width;
    return a;
}

// 20 + 20 grid lines 0.5 m apart, axes 1.5 m, three labels.
OverlayScene benchScene()
{
    OverlayScene scene;
    GridShape grid;
    grid.spacing = 0.5;
    grid.extentU = grid.extentV = 4.75;
    grid.origin = {0.25, 0.25, 0.0}; // 20 lines per direction, none through the origin
    scene.annotations.push_back(item("grid", grid, Rgba{230, 230, 230, 255}, 2.0));
    scene.annotations.push_back(item("axes", AxesShape{1.5}, kWhite, 3.0));
    const char *labels[] = {"origin", "corner A", "corner B"};
    const glm::dvec3 anchors[] = {{0, 0, 0}, {4.75, 4.75, 0}, {4.75, -4.75, 0}};
    for (int i = 0; i < 3; ++i)
        scene.annotations.push_back(item(labels[i], LabelShape{anchors[i], labels[i], {4, 4}, 20.0}, kWhite, 2.0));
    return scene;
}

StreamFormat streamFormat(const char *name, unsigned width, unsigned height)
{
    StreamFormat format;
    format.format = pixelFormatFromName(name);
    format.width = width;
    format.height = height;
    return format;
}

// The bench scene's renderer, seen by the still camera; nullptr (the benchmark skipped) if it cannot be made.
std::unique_ptr<OverlayRenderer> benchRenderer(benchmark::State &state, const char *formatName, unsigned width,
                                               unsigned height)
{
    auto renderer =
        SceneRenderer::create(benchScene(), benchCamera(width, height, 0.0), streamFormat(formatName, width, height));
    if (!renderer) {
        state.SkipWithError(renderer.error().message.c_str());
        return nullptr;
    }
    return std::move(*renderer);
}

void staticBench(benchmark::State &state, const char *formatName, unsigned width, unsigned height)
{
    const auto renderer = benchRenderer(state, formatName, width, height);
    if (!renderer)
        return;
    Ring ring(*pixelFormatFromName(formatName), width, height);
    size_t i = 0;
    for (auto _ : state)
        benchmark::DoNotOptimize(renderer->blend(ring.layout.view(ring.frame(i++)), FrameMetadata{}, 30.0).ok());
}

// Offsets from the frame's start of the cache lines the cached overlay's runs touch, in the runs' order.
std::vector<size_t> touchedLines(SceneRenderer &renderer, const FrameView &frame)
{
    const uint8_t *const base = frame.planes[0].data;
    std::vector<size_t> lines;
    for (const std::string &name : renderer.layerNames()) {
        const auto native = NativeLayer::convert(*renderer.layerPixels(name), *frame.format, Colorimetry{});
        if (!native)
            continue;
        for (const NativeRun &run : native->runs()) {
            const PlaneView &plane = frame.planes[run.plane];
            const size_t start = size_t(plane.data - base) + size_t(run.row) * plane.stride + run.byteOffset;
            for (size_t line = start / 64; line <= (start + run.length - 1) / 64; ++line) {
                if (lines.empty() || line * 64 > lines.back())
                    lines.push_back(line * 64);
            }
        }
    }
    return lines;
}

void touchBench(benchmark::State &state, const char *formatName, unsigned width, unsigned height)
{
    const auto renderer = benchRenderer(state, formatName, width, height);
    if (!renderer)
        return;
    Ring ring(*pixelFormatFromName(formatName), width, height);
    const std::vector<size_t> lines =
        touchedLines(dynamic_cast<SceneRenderer &>(*renderer), ring.layout.view(ring.frame(0)));
    constexpr size_t kAhead = 16; // prefetched as far ahead as the blend prefetches its runs
    size_t i = 0;
    for (auto _ : state) {
        uint8_t *frame = ring.frame(i++);
        for (size_t k = 0; k < lines.size(); ++k) {
            if (k + kAhead < lines.size())
                __builtin_prefetch(frame + lines[k + kAhead], 1);
            frame[lines[k]] += 1;
        }
        benchmark::ClobberMemory();
    }
    state.counters["touched_lines_%"] = 100.0 * double(lines.size()) * 64 / double(ring.layout.totalSize);
}

void dynamicBench(benchmark::State &state, const char *formatName, unsigned width, unsigned height)
{
    const auto renderer = benchRenderer(state, formatName, width, height);
    if (!renderer)
        return;
    std::vector<Camera> cameras; // made beforehand: the camera's own set-up is not the overlay's cost
    for (int k = 0; k < 64; ++k)
        cameras.push_back(benchCamera(width, height, 0.1 * (k % 16) - 0.8));
    Ring ring(*pixelFormatFromName(formatName), width, height);
    size_t i = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(renderer->setCamera(cameras[i % cameras.size()]).ok());
        benchmark::DoNotOptimize(renderer->blend(ring.layout.view(ring.frame(i++)), FrameMetadata{}, 30.0).ok());
    }
}

// config/examples/reverse_camera.toml's camera: in frame "car" (at the world origin) 1 m behind the rear axle and 1 m
// up, looking back (yaw 180) and 35 degrees down, 110 degrees across horizontally.
Camera reverseCamera(unsigned width, unsigned height)
{
    const auto viewport = Viewport::create(ViewportSpec{int(width), int(height)});
    const auto projection = Projection::perspective(FovAxis::Horizontal, 110.0, viewport->windowAspect(), 0.05, 50.0,
                                                    DepthRange::MinusOneToOne);
    const auto pose = poseFromYawPitchRoll({-1.0, 0.0, 1.0}, 180.0, 35.0, 0.0);
    return *Camera::create(*pose, *projection, Distortion{}, *viewport);
}

constexpr const char *kGuideLines = "guide lines";
constexpr double kReverseSteeringDeg = 10.0; // the example's steering_deg

// config/examples/reverse_camera.toml's annotations: the guide lines (layer "guides") and the hint (layer "hud").
OverlayScene reverseScene()
{
    OverlayScene scene;
    scene.frames.push_back(FrameSpec{"car", SceneGraph::kWorld, Transform{}});
    GuideLinesShape guide;
    guide.wheelbase = 2.7;
    guide.trackWidth = 1.6;
    guide.steeringDeg = kReverseSteeringDeg;
    guide.length = 4.0;
    guide.distanceMarks = {1.5, 2.5, 3.5};
    guide.markColours = {kRed, Rgba{255, 255, 0, 255}, kGreen};
    Annotation lines = item(kGuideLines, guide, Rgba{255, 255, 0, 255}, 4.0);
    lines.frame = "car";
    lines.style.layer = "guides";
    scene.annotations.push_back(std::move(lines));
    ScreenTextShape hint;
    hint.text = "Check surroundings for safety";
    hint.position = {400.0, 680.0};
    hint.sizePx = 22.0;
    hint.background = Rgba{0, 0, 0, 0x99};
    Annotation text = item("hint", hint, kWhite, 2.0);
    text.style.layer = "hud";
    scene.annotations.push_back(std::move(text));
    return scene;
}

// The reverse-camera scene's renderer; nullptr (the benchmark skipped) if it cannot be made.
std::unique_ptr<OverlayRenderer> reverseRenderer(benchmark::State &state, const char *formatName, unsigned width,
                                                 unsigned height)
{
    auto renderer =
        SceneRenderer::create(reverseScene(), reverseCamera(width, height), streamFormat(formatName, width, height));
    if (!renderer) {
        state.SkipWithError(renderer.error().message.c_str());
        return nullptr;
    }
    return std::move(*renderer);
}

// The road-wheel angle of frame i: a triangle wave between -30 and 30 degrees, 0.7 degrees a frame.
double sweptSteering(size_t i)
{
    constexpr double kStep = 0.7, kSpan = 60.0;
    const double phase = std::fmod(double(i) * kStep, 2.0 * kSpan);
    return phase < kSpan ? -30.0 + phase : 30.0 - (phase - kSpan);
}

// Sets the angle and blends one frame, checking that both took; false (the benchmark skipped) if not.
bool steerAndBlend(benchmark::State &state, OverlayRenderer &renderer, double steeringDeg, const FrameView &frame)
{
    if (Status status = renderer.setGuideSteering(kGuideLines, steeringDeg); !status) {
        state.SkipWithError(status.error().message.c_str());
        return false;
    }
    if (Status status = renderer.blend(frame, FrameMetadata{}, 30.0); !status) {
        state.SkipWithError(status.error().message.c_str());
        return false;
    }
    return true;
}

// Before timing, a few frames of the case's input must take the path the case is named for (drawn straight into the
// frame while the wheel turns, the cached layers while it holds still), else the figure would time something else.
void steeringBench(benchmark::State &state, const char *formatName, unsigned width, unsigned height, bool turning)
{
    const auto renderer = reverseRenderer(state, formatName, width, height);
    if (!renderer)
        return;
    const auto &scene = dynamic_cast<const SceneRenderer &>(*renderer);
    Ring ring(*pixelFormatFromName(formatName), width, height);
    for (size_t k = 0; k < 4; ++k) {
        if (!steerAndBlend(state, *renderer, turning ? sweptSteering(k) : kReverseSteeringDeg,
                           ring.layout.view(ring.frame(k))))
            return;
    }
    if (scene.drewDirectly() != turning) {
        state.SkipWithError(turning ? "a turning wheel did not draw straight into the frame"
                                    : "a steady wheel did not blend the cached layers");
        return;
    }
    // The last warm-up frame, blended once, against one no blend has reached yet: the scene must show.
    const size_t frameBytes = ring.layout.totalSize;
    size_t changed = 0;
    for (size_t b = 0; b < frameBytes; ++b)
        changed += ring.frame(3)[b] != ring.frame(ring.count - 1)[b];
    if (changed == 0) {
        state.SkipWithError("the reverse-camera scene drew nothing");
        return;
    }
    state.counters["changed_bytes_%"] = 100.0 * double(changed) / double(frameBytes);
    size_t i = 0;
    for (auto _ : state) {
        const double angle = turning ? sweptSteering(i) : kReverseSteeringDeg;
        benchmark::DoNotOptimize(renderer->setGuideSteering(kGuideLines, angle).ok());
        benchmark::DoNotOptimize(renderer->blend(ring.layout.view(ring.frame(i++)), FrameMetadata{}, 30.0).ok());
    }
    if (scene.drewDirectly() != turning)
        state.SkipWithError("the path changed while timing");
}

void steeringChangeBench(benchmark::State &state, const char *formatName, unsigned width, unsigned height)
{
    steeringBench(state, formatName, width, height, true);
}

void steadyWheelBench(benchmark::State &state, const char *formatName, unsigned width, unsigned height)
{
    steeringBench(state, formatName, width, height, false);
}

// What users write: projectPoints on the grid's end points (no near-plane clipping), cv::line and cv::putText on a
// BGR copy, and the conversion back (OpenCV has no BGR -> YUYV/NV12, so chroma is repacked by hand from 4:4:4/I420).
void toNative(const cv::Mat &bgr, const char *formatName, uint8_t *out, cv::Mat &scratch)
{
    const int w = bgr.cols, h = bgr.rows;
    if (std::strcmp(formatName, "NV12") == 0) {
        cv::cvtColor(bgr, scratch, cv::COLOR_BGR2YUV_I420);
        std::memcpy(out, scratch.data, size_t(w) * h);
        const uint8_t *u = scratch.data + size_t(w) * h, *v = u + size_t(w) * h / 4;
        uint8_t *uv = out + size_t(w) * h;
        for (size_t k = 0; k < size_t(w) * h / 4; ++k)
            uv[2 * k] = u[k], uv[2 * k + 1] = v[k];
        return;
    }
    cv::cvtColor(bgr, scratch, cv::COLOR_BGR2YUV);
    for (int y = 0; y < h; ++y) {
        const uint8_t *s = scratch.ptr(y);
        uint8_t *d = out + size_t(y) * w * 2;
        for (int x = 0; x < w; x += 2, s += 6, d += 4)
            d[0] = s[0], d[1] = uint8_t((s[1] + s[4] + 1) / 2), d[2] = s[3], d[3] = uint8_t((s[2] + s[5] + 1) / 2);
    }
}

void opencvNaiveBench(benchmark::State &state, const char *formatName, unsigned width, unsigned height)
{
    const Camera camera = benchCamera(width, height, 0.0);
    const cv::Matx33d K(0.8 * width, 0, (width - 1) / 2.0, 0, 0.8 * width, (height - 1) / 2.0, 0, 0, 1);
    // The same camera's extrinsics in OpenCV's optical frame.
    const glm::dmat4 view = camera.view();
    cv::Matx33d R;
    cv::Vec3d t;
    for (int r = 0; r < 3; ++r) {
        const double sign = r == 0 ? 1.0 : -1.0;
        for (int c = 0; c < 3; ++c)
            R(r, c) = sign * view[c][r];
        t[r] = sign * view[3][r];
    }
    cv::Vec3d rvec;
    cv::Rodrigues(R, rvec);
    std::vector<cv::Point3d> ends;
    for (int k = 0; k < 20; ++k) {
        const double c = -4.75 + 0.5 * k;
        ends.insert(ends.end(), {{c, -4.75, 0}, {c, 4.75, 0}, {-4.75, c, 0}, {4.75, c, 0}});
    }
    ends.insert(ends.end(), {{0, 0, 0}, {1.5, 0, 0}, {0, 1.5, 0}, {0, 0, 1.5}, {4.75, 4.75, 0}, {4.75, -4.75, 0}});
    const bool nv12 = std::strcmp(formatName, "NV12") == 0;
    Ring ring(*pixelFormatFromName(formatName), width, height);
    cv::Mat bgr, scratch;
    std::vector<cv::Point2d> px;
    size_t i = 0;
    for (auto _ : state) {
        uint8_t *frame = ring.frame(i++);
        const cv::Mat native(int(nv12 ? height * 3 / 2 : height), int(nv12 ? width : width), nv12 ? CV_8UC1 : CV_8UC2,
                             frame);
        cv::cvtColor(native, bgr, nv12 ? cv::COLOR_YUV2BGR_NV12 : cv::COLOR_YUV2BGR_YUYV);
        cv::projectPoints(ends, rvec, t, K, cv::noArray(), px);
        for (int k = 0; k < 80; k += 2)
            cv::line(bgr, px[k], px[k + 1], cv::Scalar(230, 230, 230), 2, cv::LINE_AA);
        const cv::Scalar axisColours[] = {{0, 0, 255}, {0, 255, 0}, {255, 0, 0}};
        for (int a = 0; a < 3; ++a)
            cv::line(bgr, px[80], px[81 + a], axisColours[a], 3, cv::LINE_AA);
        const char *labels[] = {"origin", "corner A", "corner B"};
        const int anchor[] = {80, 84, 85};
        for (int l = 0; l < 3; ++l)
            cv::putText(bgr, labels[l], px[anchor[l]] + cv::Point2d(4, 20), cv::FONT_HERSHEY_SIMPLEX, 0.7,
                        cv::Scalar::all(255), 2, cv::LINE_AA);
        toNative(bgr, formatName, frame, scratch);
        benchmark::ClobberMemory();
    }
}

} // namespace
} // namespace overlayd

int main(int argc, char **argv)
{
    using namespace overlayd;
    if (!bench::initialize(argc, argv))
        return 1;
    constexpr const char *kFamily = "BM_Blend";
    for (const bench::FrameCase &c : bench::kFrameCases) {
        bench::registerCase(kFamily, bench::kMemcpyCold, memcpyBench, c);
        bench::registerCase(kFamily, "touch", touchBench, c);
        bench::registerCase(kFamily, "static", staticBench, c);
        bench::registerCase(kFamily, "dynamic", dynamicBench, c);
        bench::registerCase(kFamily, "steering", steeringChangeBench, c);
        bench::registerCase(kFamily, "steady", steadyWheelBench, c);
        bench::registerCase(kFamily, "opencv_naive", opencvNaiveBench, c);
    }
    const auto reporter = bench::runAll();

    // The ratios from the same run (only same-run ratios mean much on a shared machine), CPU time, not wall time:
    // on a loaded machine wall time counts the time other processes held the core (all the cases are single
    // threaded and memory- or compute-bound, so on an idle machine the two agree). 0 where a case did not run.
    std::FILE *out = reporter->ratioStream();
    std::fprintf(out, "\n%-22s %14s %18s %15s %13s %16s %15s\n", "case", "static/memcpy", "naive/static",
                 "dynamic/memcpy", "static/touch", "steering/memcpy", "steady/memcpy");
    for (const bench::FrameCase &c : bench::kFrameCases) {
        const auto get = [&](const char *kind) {
            return reporter->cpuSeconds(bench::caseName(kFamily, kind, c)).value_or(0.0);
        };
        const double copy = get(bench::kMemcpyCold), fixed = get("static"), naive = get("opencv_naive"),
                     dynamic = get("dynamic"), touch = get("touch"), steering = get("steering"), steady = get("steady");
        if (copy == 0.0)
            continue;
        std::fprintf(out, "%-22s %8.3f (<=0.5) %11.1f (>=25) %9.3f (<=2) %13.2f %10.3f (<=2) %8.3f (<=0.5)\n",
                     c.name().c_str(), fixed / copy, fixed > 0 ? naive / fixed : 0.0, dynamic / copy,
                     touch > 0 ? fixed / touch : 0.0, steering / copy, steady / copy);
    }
    return 0;
}
