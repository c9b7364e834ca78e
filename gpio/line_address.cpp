// LineAddress::describe, for every message that names a line.
#include "gpio/gpio_options.h"

namespace overlayd::gpio {

std::string LineAddress::describe() const
{
    return chip + " line " + (name.empty() ? std::to_string(offset) : "'" + name + "'");
}

} // namespace overlayd::gpio
