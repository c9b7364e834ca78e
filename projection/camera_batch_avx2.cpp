// SPDX-License-Identifier: Apache-2.0
// Batch projection on 4 lanes, compiled with -mavx2 (x86-64 only); run only where the CPU reports AVX2.
#define OVERLAYD_LANES_NS avx2_lanes
#include "camera_batch.h"

#include "camera_batch_kernel.h"

namespace overlayd::avx2 {

void projectPoints(const BatchJob &job)
{
    OVERLAYD_LANES_NS::projectPointsWith<OVERLAYD_LANES_NS::Lanes4>(job);
}

} // namespace overlayd::avx2
