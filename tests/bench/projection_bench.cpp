// projection_bench: Camera::projectPoints against cv::projectPoints / cv::fisheye::projectPoints, same points.
//
// Usage: projection_bench [--points=N] [Google Benchmark flags]. Before any timing, every model's pixels are
// checked against OpenCV's (max difference <= 1e-6 px) for every batch loop this CPU runs; a mismatch aborts the
// run, so a fast wrong answer can never be reported. At the end a "ratio" line per model gives both costs per
// point and the speed-up of the default loop (wall clock), and a "kernel" line per loop and model gives wall-clock
// and CPU-time ratios (CPU time is the steadier figure on a shared machine).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <random>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

#include "projection/camera.h"

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
    {"overlayd", BatchKernel::Best},
    {"overlayd-lanes2", BatchKernel::Lanes2},
    {"overlayd-avx2", BatchKernel::Lanes4Avx2},
    {"overlayd-avx512", BatchKernel::Lanes8Avx512},
};

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

std::map<std::string, Fixture> fixtures;

[[noreturn]] void fail(const std::string &message)
{
    std::fprintf(stderr, "projection_bench: %s\n", message.c_str());
    std::exit(EXIT_FAILURE);
}

void setUp(const Model &model, std::size_t points)
{
    Fixture &f = fixtures[model.name];
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
        std::printf("verified %s (%s): %zu points, max |overlayd - OpenCV| = %.3g px\n", model.name, k.name, points,
                    worst);
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

// Console output as usual, plus the real and CPU time per point of every run, keyed by benchmark name. CPU time
// is the steadier figure on a shared machine (time spent descheduled does not count).
class RecordingReporter : public benchmark::ConsoleReporter
{
public:
    explicit RecordingReporter(std::size_t points) : points_(points) {}

    void ReportRuns(const std::vector<Run> &runs) override
    {
        ConsoleReporter::ReportRuns(runs);
        for (const Run &run : runs)
            if (run.run_type == Run::RT_Iteration && run.iterations > 0) {
                const double scale = 1e9 / (static_cast<double>(run.iterations) * points_);
                nsPerPoint[run.benchmark_name()] = run.real_accumulated_time * scale;
                cpuNsPerPoint[run.benchmark_name()] = run.cpu_accumulated_time * scale;
            }
    }

    std::map<std::string, double> nsPerPoint;
    std::map<std::string, double> cpuNsPerPoint;

private:
    std::size_t points_;
};

} // namespace

int main(int argc, char **argv)
{
    std::size_t points = 1'000'000;
    // Take --points=N out of argv before Google Benchmark sees (and rejects) it.
    int kept = 1;
    for (int i = 1; i < argc; ++i) {
        if (std::strncmp(argv[i], "--points=", 9) == 0)
            points = std::strtoull(argv[i] + 9, nullptr, 10);
        else
            argv[kept++] = argv[i];
    }
    argc = kept;
    if (points == 0)
        fail("--points must be a positive number");

    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv))
        return EXIT_FAILURE;

    for (const Model &model : kModels) {
        setUp(model, points);
        const std::string name = model.name;
        benchmark::RegisterBenchmark(("opencv/" + name).c_str(), benchOpenCv, name)->Unit(benchmark::kMillisecond);
        for (const KernelChoice &k : kKernels)
            if (Camera::batchKernelAvailable(k.kernel))
                benchmark::RegisterBenchmark((std::string(k.name) + "/" + name).c_str(), benchOverlayd, name, k.kernel)
                    ->Unit(benchmark::kMillisecond);
    }

    RecordingReporter reporter(points);
    benchmark::RunSpecifiedBenchmarks(&reporter);
    benchmark::Shutdown();

    // "ratio" lines: the default loop, wall-clock time (what scripts/test.sh prints); "kernel" lines: every loop,
    // both clocks.
    for (const KernelChoice &k : kKernels) {
        for (const Model &model : kModels) {
            const std::string name = model.name;
            const auto cv = reporter.nsPerPoint.find("opencv/" + name);
            const auto ours = reporter.nsPerPoint.find(std::string(k.name) + "/" + name);
            if (cv == reporter.nsPerPoint.end() || ours == reporter.nsPerPoint.end())
                continue; // filtered out by --benchmark_filter, or not available on this CPU
            const double cvCpu = reporter.cpuNsPerPoint[cv->first], oursCpu = reporter.cpuNsPerPoint[ours->first];
            if (k.kernel == BatchKernel::Best)
                std::printf("ratio %s: cv %.2f ns/point, overlayd %.2f ns/point, speed-up %.2fx\n", name.c_str(),
                            cv->second, ours->second, cv->second / ours->second);
            std::printf("kernel %s %s: wall cv %.2f / %.2f ns/point = %.2fx; cpu cv %.2f / %.2f ns/point = %.2fx\n",
                        k.name, name.c_str(), cv->second, ours->second, cv->second / ours->second, cvCpu, oursCpu,
                        cvCpu / oursCpu);
        }
    }
    return EXIT_SUCCESS;
}
