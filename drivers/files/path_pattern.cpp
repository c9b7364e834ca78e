// SPDX-License-Identifier: Apache-2.0
// A tiny parser for the one printf conversion image sequences use.
#include "drivers/files/path_pattern.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <filesystem>

namespace overlayd {

namespace {

struct Parsed {
    std::string prefix, suffix;
    unsigned width = 0;
    bool zeroPad = false;
    bool found = false;
};

Result<Parsed> parse(const std::string &pattern)
{
    Parsed parsed;
    std::string *out = &parsed.prefix;
    for (size_t i = 0; i < pattern.size(); ++i) {
        if (pattern[i] != '%') {
            out->push_back(pattern[i]);
            continue;
        }
        if (i + 1 < pattern.size() && pattern[i + 1] == '%') {
            out->push_back('%'), ++i;
            continue;
        }
        size_t j = i + 1;
        const bool zero = j < pattern.size() && pattern[j] == '0';
        unsigned width = 0;
        for (; j < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[j])) && width < 100; ++j)
            width = width * 10 + unsigned(pattern[j] - '0');
        if (j >= pattern.size() || pattern[j] != 'd' || parsed.found || width > 20)
            return makeError(ErrorCode::InvalidArgument,
                             "'" + pattern + "': only one %d (or %0Nd) is allowed in a numbered path");
        parsed.found = true, parsed.zeroPad = zero, parsed.width = width;
        out = &parsed.suffix;
        i = j;
    }
    return parsed;
}

} // namespace

bool hasIndexPattern(const std::string &pattern)
{
    const auto parsed = parse(pattern);
    return parsed && parsed->found;
}

Result<std::string> formatIndex(const std::string &pattern, uint64_t index)
{
    auto parsed = parse(pattern);
    if (!parsed)
        return parsed.error();
    if (!parsed->found)
        return parsed->prefix;
    std::string digits = std::to_string(index);
    if (digits.size() < parsed->width)
        digits.insert(0, parsed->width - digits.size(), parsed->zeroPad ? '0' : ' ');
    return parsed->prefix + digits + parsed->suffix;
}

std::string lowerExtension(const std::string &path)
{
    std::string extension = std::filesystem::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return extension;
}

} // namespace overlayd
