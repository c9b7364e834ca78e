// SPDX-License-Identifier: Apache-2.0
// Range's refusal text: limits print short (1e+06), a value given with every digit a user may have typed.
#include "base/number_range.h"

#include "base/number_text.h"

namespace overlayd {

std::string Range::describe() const
{
    return (minOpen ? "(" : "[") + shortNumber(min) + ", " + shortNumber(max) + "]";
}

std::string Range::refusal(double value) const
{
    if (contains(value))
        return {};
    return "out of range: must be in " + describe() + " (got " + shortNumber(value, 15) + ")";
}

std::string numbersRefusal(const std::vector<double> &values, const std::vector<std::string> &names,
                           const std::string &group, const Range &range)
{
    for (size_t i = 0; i < values.size(); ++i)
        if (const std::string why = range.refusal(values[i]); !why.empty())
            return names[i % names.size()] + " of " + group + " " + std::to_string(i / names.size() + 1) + ": " + why;
    return {};
}

} // namespace overlayd
