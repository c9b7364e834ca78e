// Numbers as text without a fixed-size buffer: printf formats into a string sized by the formatted length, so a
// large value (1e300 with "%.6f" is 308 digits) is printed whole, never truncated.
#pragma once

#include <string>

namespace overlayd {

// printf's format, into a string as long as the result.
std::string formatted(const char *format, ...) __attribute__((format(printf, 1, 2)));

// A number with `precision` significant digits, as "%.*g" (1e+06, 0.1, nan, inf).
std::string shortNumber(double value, int precision = 6);

} // namespace overlayd
