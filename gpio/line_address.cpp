// SPDX-License-Identifier: Apache-2.0
// LineAddress::describe, for every message that names a line, and sameLine, for a line claimed twice.
#include "gpio/gpio_options.h"

#include <algorithm>
#include <cctype>

namespace overlayd {

namespace {

// The chip's device name as libgpiod v1's gpiod_chip_open_lookup() resolves a spelling without the chip: a number
// N is /dev/gpiochipN, "/dev/NAME" is NAME; anything else (a name or a label) as written.
std::string chipDevice(const std::string &chip)
{
    const auto digit = [](char c) {
        return std::isdigit(static_cast<unsigned char>(c)) != 0;
    };
    if (!chip.empty() && chip.size() <= 9 && std::all_of(chip.begin(), chip.end(), digit))
        return "gpiochip" + std::to_string(std::stoul(chip));
    constexpr std::string_view kDev = "/dev/";
    if (chip.starts_with(kDev) && chip.find('/', kDev.size()) == std::string::npos)
        return chip.substr(kDev.size());
    return chip;
}

} // namespace

std::string LineAddress::describe() const
{
    return chip + " line " + (name.empty() ? std::to_string(offset) : "'" + name + "'");
}

bool LineAddress::sameLine(const LineAddress &other) const
{
    return name == other.name && offset == other.offset && chipDevice(chip) == chipDevice(other.chip);
}

} // namespace overlayd
