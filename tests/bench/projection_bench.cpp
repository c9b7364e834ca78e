// SPDX-License-Identifier: Apache-2.0
// projection_bench: Camera::projectPoints against cv::projectPoints / cv::fisheye::projectPoints, same points.
//
// Usage: projection_bench [--points=N[,N...]] [Google Benchmark flags]; 1000 and 100000 points unless given.
// Before any timing, every model's pixels are checked against OpenCV's (max difference <= 1e-6 px) for every batch
// loop this CPU runs; a mismatch aborts the run, so a fast wrong answer can never be reported.
//
// Cases are named BM_Project/<who>/<model>/<points>: who is opencv, ours (the loop Camera::projectPoints picks on
// this CPU) or ours_lanes2 / ours_avx2 / ours_avx512 (each loop forced). At the end a "ratio" line per model and
// size gives OpenCV's and the picked loop's CPU time per point and the speed-up, and a "kernel" line the same for
// every loop (scripts/test.sh prints the ratio lines; scripts/bench.sh reads the JSON of the same runs).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

#include "projection/camera.h"
#include "tests/bench_support/same_run.h"

namespace {

using namespace overlayd;

constexpr double kMaxDifferencePx = 1e-6;

struct Model {
    const char *name;
    DistortionModel model;
    std::array<double, 8> coeffs;
    double focal;       // fx = fy, pixels
    double fieldRadius; // normalized radius the random points reach: a little beyond the image's corners
};

const Model kModels[] = {
    {"none", DistortionModel::None, {}, 1000.0, 1.2},
    {"radtan5", DistortionModel::RadialTangential, {-0.28, 0.07, 1e-4, -2e-4, -0.005}, 1000.0, 1.2},
    {"fisheye", DistortionModel::Fisheye, {0.05, -0.01, 0.002, -0.0005}, 500.0, std::tan(70.0 * M_PI / 180.0)},
};

// The batch loops timed besides the default one (Best), where this CPU can run them.
struct KernelChoice {
    const char *name;
    BatchKernel kernel;
};
const KernelChoice kKernels[] = {
    {"ours", BatchKernel::Best},
    {"ours_lanes2", BatchKernel::Lanes2},
    {"ours_avx2", BatchKernel::Lanes4Avx2},
    {"ours_avx512", BatchKernel::Lanes8Avx512},
};

const char *kernelName(BatchKernel kernel)
{
    for (const KernelChoice &k : kKernels)
        if (k.kernel == kernel)
            return k.name;
    return "?";
}

// One model's camera (for both libraries) and the shared input points.
struct Fixture {
    const Model *model = nullptr;
    std::optional<Camera> camera;
    cv::Vec3d rvec{0.3, -0.2, 0.1}, tvec{0.5, -1.0, 2.0};
    cv::Matx33d k;
    std::vector<glm::dvec3> world;
    std::vector<cv::Point3d> object;
    std::vector<ProjectedPoint> ours;
    std::vector<cv::Point2d> theirs;

    void cvProject()
    {
        const auto &c = model->coeffs;
        if (model->model == DistortionModel::Fisheye)
            cv::fisheye::projectPoints(object, theirs, rvec, tvec, k, cv::Vec4d(c[0], c[1], c[2], c[3]));
        else if (model->model == DistortionModel::None)
            cv::projectPoints(object, rvec, tvec, k, cv::noArray(), theirs);
        else
            cv::projectPoints(object, rvec, tvec, k, cv::Vec<double, 5>(c[0], c[1], c[2], c[3], c[4]), theirs);
    }
    void ourProject(BatchKernel kernel = BatchKernel::Best) { camera->projectPoints(world, ours, kernel); }
};

// Keyed by "<model>/<points>".
std::map<std::string, Fixture> fixtures;

[[noreturn]] void fail(const std::string &message)
{
    std::fprintf(stderr, "projection_bench: %s\n", message.c_str());
    std::exit(EXIT_FAILURE);
}

std::string caseName(const Model &model, std::size_t points)
{
    return std::string(model.name) + "/" + std::to_string(points);
}

void setUp(const Model &model, std::size_t points)
{
    Fixture &f = fixtures[caseName(model, points)];
    f.model = &model;
    const int width = 1920, height = 1080;
    const PinholeIntrinsics intrinsics{model.focal, model.focal, 959.5, 539.5, 0.0, width, height};
    f.k = cv::Matx33d(model.focal, 0, 959.5, 0, model.focal, 539.5, 0, 0, 1);
    auto pose = poseFromRodrigues({f.rvec[0], f.rvec[1], f.rvec[2]}, {f.tvec[0], f.tvec[1], f.tvec[2]});
    auto projection = Projection::pinhole(intrinsics, 0.01, 1000.0, DepthRange::ZeroToOne);
    auto viewport = Viewport::create({width, height});
    auto camera = Camera::create(*pose, *projection, Distortion{model.model, model.coeffs}, *viewport);
    if (!camera)
        fail(std::string("cannot build the ") + model.name + " camera: " + camera.error().message);
    f.camera = std::move(*camera);

    // Points in the optical frame at depth 1..100 within the field, taken to the world frame by OpenCV's rotation.
    cv::Matx33d r;
    cv::Rodrigues(f.rvec, r);
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    f.world.resize(points);
    f.object.resize(points);
    for (std::size_t i = 0; i < points; ++i) {
        const double radius = model.fieldRadius * std::sqrt(unit(rng)), phi = 2.0 * M_PI * unit(rng);
        const double z = 1.0 + 99.0 * unit(rng);
        const cv::Vec3d optical(radius * std::cos(phi) * z, radius * std::sin(phi) * z, z);
        const cv::Vec3d w = r.t() * (optical - f.tvec);
        f.world[i] = {w[0], w[1], w[2]};
        f.object[i] = {w[0], w[1], w[2]};
    }
    f.ours.resize(points);
    f.theirs.resize(points);

    // Verify before timing anything, every loop this CPU runs.
    f.cvProject();
    for (const KernelChoice &k : kKernels) {
        if (!Camera::batchKernelAvailable(k.kernel))
            continue;
        f.ourProject(k.kernel);
        double worst = 0.0;
        for (std::size_t i = 0; i < points; ++i) {
            if (f.ours[i].status == PointStatus::Clipped)
                fail(std::string(model.name) + ": point " + std::to_string(i) + " was clipped; OpenCV projects it");
            worst = std::max(
                {worst, std::abs(f.ours[i].pixel.x - f.theirs[i].x), std::abs(f.ours[i].pixel.y - f.theirs[i].y)});
        }
        if (!(worst <= kMaxDifferencePx))
            fail(std::string(model.name) + " (" + k.name + "): overlayd and OpenCV differ by up to " +
                 std::to_string(worst) + " px (allowed " + std::to_string(kMaxDifferencePx) +
                 "); not timing a wrong answer");
        // stderr: stdout carries the JSON under --benchmark_format=json.
        std::fprintf(stderr, "verified %s (%s): %zu points, max |overlayd - OpenCV| = %.3g px\n", model.name, k.name,
                     points, worst);
    }
}

void setCounters(benchmark::State &state, std::size_t points)
{
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * points));
    // Seconds per point, shown with an SI prefix: "36n" is 36 ns/point.
    state.counters["per_point"] = benchmark::Counter(
        static_cast<double>(points), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void benchOverlayd(benchmark::State &state, const std::string &name, BatchKernel kernel)
{
    Fixture &f = fixtures.at(name);
    if (kernel == BatchKernel::Best) // which loop that is, in every report (the JSON's "label")
        state.SetLabel(std::string("runs ") + kernelName(Camera::bestBatchKernel()));
    for (auto _ : state) {
        f.ourProject(kernel);
        benchmark::DoNotOptimize(f.ours.data());
        benchmark::ClobberMemory();
    }
    setCounters(state, f.world.size());
}

void benchOpenCv(benchmark::State &state, const std::string &name)
{
    Fixture &f = fixtures.at(name);
    for (auto _ : state) {
        f.cvProject();
        benchmark::DoNotOptimize(f.theirs.data());
        benchmark::ClobberMemory();
    }
    setCounters(state, f.world.size());
}

std::string benchName(const char *who, const Model &model, std::size_t points)
{
    return std::string("BM_Project/").append(who).append("/").append(caseName(model, points));
}

// "<what> <model> <points>: cv X / ours Y ns/point = Zx" from CPU time; nothing if either case did not run.
void printRatio(const bench::SameRunReporter &reporter, const char *what, const char *kernel, const Model &model,
                std::size_t points)
{
    const std::optional<double> cv = reporter.cpuSeconds(benchName("opencv", model, points));
    const std::optional<double> ours = reporter.cpuSeconds(benchName(kernel, model, points));
    if (!cv || !ours)
        return; // filtered out by --benchmark_filter, or not available on this CPU
    const double scale = 1e9 / static_cast<double>(points);
    std::fprintf(reporter.ratioStream(), "%s %s %zu points: cv %.2f ns/point, %s %.2f ns/point, speed-up %.2fx\n", what,
                 model.name, points, *cv * scale, kernel, *ours * scale, *cv / *ours);
}

} // namespace

int main(int argc, char **argv)
{
    std::vector<std::size_t> sizes{1000, 100'000};
    // Take --points=N[,N...] out of argv before Google Benchmark sees (and rejects) it.
    int kept = 1;
    for (int i = 1; i < argc; ++i) {
        if (std::strncmp(argv[i], "--points=", 9) == 0) {
            sizes.clear();
            for (const char *p = argv[i] + 9; *p;) {
                char *end = nullptr;
                sizes.push_back(std::strtoull(p, &end, 10));
                if (end == p || sizes.back() == 0 || (*end != ',' && *end != '\0'))
                    fail("--points takes positive numbers separated by commas");
                p = *end ? end + 1 : end;
            }
        } else {
            argv[kept++] = argv[i];
        }
    }
    argc = kept;
    if (sizes.empty())
        fail("--points takes positive numbers separated by commas");

    if (!bench::initialize(argc, argv))
        return EXIT_FAILURE;

    for (const std::size_t points : sizes)
        for (const Model &model : kModels) {
            setUp(model, points);
            const std::string name = caseName(model, points);
            benchmark::RegisterBenchmark(benchName("opencv", model, points).c_str(), benchOpenCv, name)
                ->Unit(benchmark::kMicrosecond);
            for (const KernelChoice &k : kKernels)
                if (Camera::batchKernelAvailable(k.kernel)) {
                    benchmark::RegisterBenchmark(benchName(k.name, model, points).c_str(), benchOverlayd, name,
                                                 k.kernel)
                        ->Unit(benchmark::kMicrosecond);
                }
        }

    const auto reporter = bench::runAll();
    for (const std::size_t points : sizes)
        for (const Model &model : kModels)
            printRatio(*reporter, "ratio", "ours", model, points);
    for (const KernelChoice &k : kKernels)
        if (k.kernel != BatchKernel::Best)
            for (const std::size_t points : sizes)
                for (const Model &model : kModels)
                    printRatio(*reporter, "kernel", k.name, model, points);
    return EXIT_SUCCESS;
}
