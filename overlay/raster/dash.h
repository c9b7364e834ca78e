// Dash patterns along drawn curves.
#pragma once

#include <span>

#include "projection/polylines.h"

namespace overlayd {

// The shortest dash period (on + off + ...) in pixels: a finer pattern cannot be seen, and walking it would cost one
// step per interval (a 1e-9 px dash along a 1000 px line is 10^12 steps). The config refuses a shorter one; the
// renderer draws one it is given anyway as solid, so no scene can make it loop without end.
inline constexpr double kMinDashPeriodPx = 1.0;

// Appends the "on" pieces of every polyline of `in` to `out`: pattern is on, off, on, off... in pixels of arc
// length along each polyline (restarting at each), so a dash follows a curve through the lens. An empty pattern,
// or one shorter than kMinDashPeriodPx, copies `in`.
void applyDash(const Polylines &in, std::span<const double> pattern, Polylines &out);

} // namespace overlayd
