// SPDX-License-Identifier: Apache-2.0
// Dash patterns along drawn curves.
#pragma once

#include <span>

#include "overlay/shapes/annotation.h"
#include "projection/polylines.h"

namespace overlayd {

// Appends the "on" pieces of every polyline of `in` to `out`: pattern is on, off, on, off... in pixels of arc
// length along each polyline (restarting at each), so a dash follows a curve through the lens. An empty pattern,
// or one shorter than kMinDashPeriodPx, copies `in`.
void applyDash(const Polylines &in, std::span<const double> pattern, Polylines &out);

} // namespace overlayd
