// SPDX-License-Identifier: Apache-2.0
// Range: the interval a number from outside (a config key, a command-line argument, a points file, an API body)
// must lie in, with the refusal that names it. One definition, so that every door applies the config file's ranges.
#pragma once

#include <string>
#include <vector>

namespace overlayd {

// Every number from outside must lie in a range; without a narrower one, this (metres of a position or a size,
// pixels, coefficients): 1000 km. Beyond it a value is a typing mistake, and products of such values (a frame
// chain, a projection) lose every digit or overflow to inf.
inline constexpr double kMaxMagnitude = 1e6;

// [min, max], or (min, max] when minOpen (sizes, fps, focal lengths: > 0). NaN is in no range.
struct Range {
    double min = -kMaxMagnitude;
    double max = kMaxMagnitude;
    bool minOpen = false;
    bool contains(double value) const { return (minOpen ? value > min : value >= min) && value <= max; }
    std::string describe() const;
    // "" when the value is in range, else "out of range: must be in [min, max] (got value)".
    std::string refusal(double value) const;
};
inline constexpr Range kAnyMagnitude{};

// Numbers from the command line or an API body, checked before use: "" when each lies in `range`, else the first one
// out named by its place ("X of point 2", cycling `names` over groups of names.size() called `group`) and the range.
std::string numbersRefusal(const std::vector<double> &values, const std::vector<std::string> &names,
                           const std::string &group, const Range &range);

} // namespace overlayd
