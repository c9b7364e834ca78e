// SPDX-License-Identifier: Apache-2.0
// Numbers as text without a fixed-size buffer: printf formats into a string sized by the formatted length, so a
// large value (1e300 with "%.6f" is 308 digits) is printed whole, never truncated.
#pragma once

#include <string>

namespace overlayd {

// printf's format, into a string as long as the result.
std::string formatted(const char *format, ...) __attribute__((format(printf, 1, 2)));

// A number a person reads, rounded to `decimals` places (1e-6 m is a micrometre): -6.000000000000003 is -6 and
// 6.8e-17 is 0 (never -0), and the shortest text of the result is its decimal form. A value too large to have
// such digits, or not finite, is returned as it is.
double roundedTo(double value, int decimals);

// A number with `precision` significant digits, as "%.*g" (1e+06, 0.1, nan, inf).
std::string shortNumber(double value, int precision = 6);

} // namespace overlayd
