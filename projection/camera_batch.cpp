// SPDX-License-Identifier: Apache-2.0
// The 2-lane batch loop every CPU runs (Camera::projectPoints, in camera.cpp, picks a wider one where the CPU has
// it).
#include "camera_batch.h"
#include "camera_batch_kernel.h"

namespace overlayd {

namespace baseline {

void projectPoints(const BatchJob &job)
{
    OVERLAYD_LANES_NS::projectPointsWith<OVERLAYD_LANES_NS::Lanes2>(job);
}

} // namespace baseline

} // namespace overlayd
