// SPDX-License-Identifier: Apache-2.0
// `overlayd list-gpio`: what a user puts under [[gpio.input]] / [[gpio.output]] — chips by name and label, lines by
// offset and name, and who holds each line now.
#include <cstdio>
#include <string>

#include "base/json_text.h"
#include "gpio/line_provider.h"
#include "tools/commands.h"

namespace overlayd {

namespace {

std::string asJson(const std::vector<ChipInfo> &chips)
{
    std::string out = "[";
    for (size_t c = 0; c < chips.size(); ++c) {
        const ChipInfo &chip = chips[c];
        out += std::string(c ? ",\n " : "\n ") + "{\"name\": " + jsonString(chip.name) +
               ", \"label\": " + jsonString(chip.label) + ", \"path\": " + jsonString(chip.path) + ", \"lines\": [";
        for (size_t l = 0; l < chip.lines.size(); ++l) {
            const LineInfo &line = chip.lines[l];
            out += std::string(l ? ", " : "") + "{\"offset\": " + std::to_string(line.offset) +
                   ", \"name\": " + jsonString(line.name) + ", \"consumer\": " + jsonString(line.consumer) +
                   ", \"direction\": " + (line.output ? "\"output\"" : "\"input\"") +
                   ", \"active_low\": " + (line.activeLow ? "true" : "false") + "}";
        }
        out += "]}";
    }
    return out + (chips.empty() ? "]\n" : "\n]\n");
}

std::string asText(const std::vector<ChipInfo> &chips)
{
    if (chips.empty())
        return "no GPIO chips found (/dev/gpiochip*)\n";
    std::string out;
    for (const ChipInfo &chip : chips) {
        out +=
            chip.name + " '" + chip.label + "' (" + chip.path + ", " + std::to_string(chip.lines.size()) + " lines)\n";
        for (const LineInfo &line : chip.lines) {
            out += "  line " + std::to_string(line.offset) + (line.name.empty() ? " unnamed" : " '" + line.name + "'") +
                   (line.output ? " output" : " input") + (line.activeLow ? " active-low" : "");
            out += line.consumer.empty() ? "\n" : " held by '" + line.consumer + "'\n";
        }
    }
    return out;
}

} // namespace

int listGpioCommand(bool json)
{
    auto chips = listChips();
    if (!chips) {
        std::fprintf(stderr, "overlayd: list-gpio: %s\n", chips.error().message.c_str());
        return 1;
    }
    const std::string text = json ? asJson(*chips) : asText(*chips);
    std::fputs(text.c_str(), stdout);
    return 0;
}

} // namespace overlayd
