// SPDX-License-Identifier: Apache-2.0
// Batch projection on 8 lanes, compiled with -mavx512f (x86-64 only); run only where the CPU reports AVX-512F.
#define OVERLAYD_LANES_NS avx512_lanes
#include "camera_batch.h"

#include "camera_batch_kernel.h"

namespace overlayd::avx512 {

void projectPoints(const BatchJob &job)
{
    OVERLAYD_LANES_NS::projectPointsWith<OVERLAYD_LANES_NS::Lanes8>(job);
}

} // namespace overlayd::avx512
