// SPDX-License-Identifier: Apache-2.0
// drivers_timing: CPU time (not wall time: the build machine is shared) of the synthetic source's costly steps at
// 1280x720 YUYV. A measurement tool, not a test: run build-*/tests/unit/drivers/drivers_timing.
#include <cstdio>
#include <ctime>

#include "drivers/source_options.h"

namespace {

using namespace overlayd;

double cpuSeconds()
{
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) + double(t.tv_nsec) * 1e-9;
}

Result<Camera> demoCamera()
{
    auto pose = poseLookAt({-3.0, -4.0, 1.6}, {1.0, 0.5, 0.0}, {0.0, 0.0, 1.0});
    auto projection =
        Projection::pinhole({746.0, 746.0, 639.5, 359.5, 0.0, 1280, 720}, 0.05, 200.0, DepthRange::ZeroToOne);
    auto viewport = Viewport::create({1280, 720});
    if (!pose || !projection || !viewport)
        return makeError(ErrorCode::InvalidArgument, "demo camera");
    return Camera::create(*pose, *projection,
                          Distortion{DistortionModel::RadialTangential, {-0.28, 0.08, 0.0005, -0.0003, -0.01}},
                          *viewport);
}

// Milliseconds of CPU for start() and per frame over `frames` frames.
void measure(const char *name, const SourceOptions &options, int frames, const Camera *camera = nullptr)
{
    auto source = makeSource(options, camera);
    if (!source) {
        std::printf("%s: %s\n", name, source.error().message.c_str());
        return;
    }
    const double t0 = cpuSeconds();
    if (!(*source)->start())
        return;
    const double t1 = cpuSeconds();
    for (int i = 0; i < frames; ++i)
        (void)(*source)->nextFrame();
    const double t2 = cpuSeconds();
    std::printf("%-40s start %8.1f ms   per frame %7.2f ms\n", name, (t1 - t0) * 1e3, (t2 - t1) * 1e3 / frames);
}

} // namespace

int main()
{
    SourceOptions options;
    options.pixelFormat = pixelFormatFromName("YUYV");
    options.synthetic.checkerMetres = 0.5;
    auto camera = demoCamera();
    if (!camera)
        return 1;
    measure("checkerboard-scene (radtan lens)", options, 100, &*camera);
    options.synthetic.pattern = SyntheticPattern::MovingGradient;
    measure("moving-gradient", options, 30);
    options.synthetic.pattern = SyntheticPattern::Noise;
    measure("noise", options, 30);
    options.synthetic.pattern = SyntheticPattern::ColourBars;
    measure("colour-bars", options, 100);
    return 0;
}
