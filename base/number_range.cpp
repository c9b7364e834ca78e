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

} // namespace overlayd
