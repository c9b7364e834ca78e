// SPDX-License-Identifier: Apache-2.0
// formatted(): vsnprintf asked for the length first, then into a string of that length.
#include "base/number_text.h"

#include <cmath>
#include <cstdarg>
#include <cstdio>

namespace overlayd {

std::string formatted(const char *format, ...)
{
    va_list arguments;
    va_start(arguments, format);
    va_list again;
    va_copy(again, arguments);
    const int length = std::vsnprintf(nullptr, 0, format, arguments);
    va_end(arguments);
    std::string text;
    if (length > 0) {
        text.resize(size_t(length) + 1); // vsnprintf writes the terminating NUL too
        std::vsnprintf(text.data(), text.size(), format, again);
        text.resize(size_t(length));
    }
    va_end(again);
    return text;
}

std::string shortNumber(double value, int precision)
{
    return formatted("%.*g", precision, value);
}

double roundedTo(double value, int decimals)
{
    const double scale = std::pow(10.0, decimals);
    // Dividing the rounded integer by an exact power of ten gives the double nearest the decimal, as parsing it would.
    if (!std::isfinite(value) || std::abs(value * scale) >= 0x1p52)
        return value;
    return std::round(value * scale) / scale + 0.0;
}

} // namespace overlayd
