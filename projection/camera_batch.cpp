// SPDX-License-Identifier: Apache-2.0
// Camera::projectPoints: the 2-lane batch loop every CPU runs, and the choice of a wider one where the CPU has it.
#include "camera.h"

#include <algorithm>

#include "camera_batch.h"
#include "camera_batch_kernel.h"

namespace overlayd {

namespace baseline {

void projectPoints(const BatchJob &job)
{
    OVERLAYD_LANES_NS::projectPointsWith<OVERLAYD_LANES_NS::Lanes2>(job);
}

} // namespace baseline

bool Camera::batchKernelAvailable(BatchKernel kernel)
{
    switch (kernel) {
    case BatchKernel::Best:
    case BatchKernel::Lanes2:
        return true;
#ifdef OVERLAYD_HAVE_X86_KERNELS
    // libgcc reads CPUID once at start-up; it also checks that the OS saves the AVX / AVX-512 registers.
    case BatchKernel::Lanes4Avx2:
        return __builtin_cpu_supports("avx2");
    case BatchKernel::Lanes8Avx512:
        return __builtin_cpu_supports("avx512f");
#else
    case BatchKernel::Lanes4Avx2:
    case BatchKernel::Lanes8Avx512:
        return false;
#endif
    }
    return false;
}

BatchKernel Camera::bestBatchKernel()
{
    return batchKernelAvailable(BatchKernel::Lanes8Avx512) ? BatchKernel::Lanes8Avx512
           : batchKernelAvailable(BatchKernel::Lanes4Avx2) ? BatchKernel::Lanes4Avx2
                                                           : BatchKernel::Lanes2;
}

void Camera::projectPoints(std::span<const glm::dvec3> world, std::span<ProjectedPoint> out, BatchKernel kernel) const
{
    const BatchJob job{path_,        viewProjection_, lens_ ? lens_->distortion().model : DistortionModel::None,
                       world.data(), out.data(),      std::min(world.size(), out.size())};
    if (kernel == BatchKernel::Best)
        kernel = bestBatchKernel();
    else if (!batchKernelAvailable(kernel))
        kernel = BatchKernel::Lanes2;
#ifdef OVERLAYD_HAVE_X86_KERNELS
    if (kernel == BatchKernel::Lanes8Avx512)
        return avx512::projectPoints(job);
    if (kernel == BatchKernel::Lanes4Avx2)
        return avx2::projectPoints(job);
#endif
    baseline::projectPoints(job);
}

} // namespace overlayd
