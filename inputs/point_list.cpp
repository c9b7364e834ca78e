// SPDX-License-Identifier: Apache-2.0
// std::from_chars reads each number (no locale, no allocation, the whole token must be a number; decimal or
// scientific notation, an optional sign).
#include "inputs/point_list.h"

#include "base/number_range.h"

#include <charconv>
#include <cmath>

#include "base/utf8.h"

namespace overlayd {

namespace {

// How much of a refused token a message quotes (whole characters, invalid bytes as \xNN).
constexpr size_t kQuotedTokenBytes = 32;

bool isSeparator(char c)
{
    return c == ' ' || c == '\t' || c == ',' || c == '\r';
}

} // namespace

Result<std::vector<glm::dvec3>> parsePointList(std::string_view text, const std::string &name)
{
    std::vector<glm::dvec3> points;
    size_t lineNumber = 0;
    while (!text.empty()) {
        ++lineNumber;
        const size_t end = text.find('\n');
        std::string_view line = text.substr(0, end);
        text = end == std::string_view::npos ? std::string_view() : text.substr(end + 1);
        if (const size_t hash = line.find('#'); hash != std::string_view::npos)
            line = line.substr(0, hash);
        const auto where = [&] {
            return name + ":" + std::to_string(lineNumber) + ": ";
        };
        double values[3];
        int count = 0;
        for (size_t at = 0; at < line.size();) {
            if (isSeparator(line[at])) {
                ++at;
                continue;
            }
            size_t stop = at;
            while (stop < line.size() && !isSeparator(line[stop]))
                ++stop;
            const std::string_view token = line.substr(at, stop - at);
            if (count == 3)
                return makeError(ErrorCode::Malformed, where() + "more than 3 numbers (expected \"x y z\")");
            double value = 0.0;
            // from_chars takes no leading '+', which other programs write.
            const char *first = token.data() + (token.size() > 1 && token[0] == '+' && token[1] != '-' ? 1 : 0);
            const auto [ptr, error] = std::from_chars(first, token.data() + token.size(), value);
            if (error != std::errc() || ptr != token.data() + token.size() || !std::isfinite(value))
                return makeError(ErrorCode::Malformed,
                                 where() + "'" + quotable(token, kQuotedTokenBytes) + "' is not a finite number");
            if (const std::string why = kAnyMagnitude.refusal(value); !why.empty())
                return makeError(ErrorCode::Malformed, where() + "xyz"[count] + ": " + why);
            values[count++] = value;
            at = stop;
        }
        if (count == 0)
            continue;
        if (count != 3)
            return makeError(ErrorCode::Malformed,
                             where() + std::to_string(count) + " number(s); expected \"x y z\" in metres");
        if (points.size() == kMaxPathPoints)
            return makeError(ErrorCode::Malformed, where() + "more than " + std::to_string(kMaxPathPoints) + " points");
        points.emplace_back(values[0], values[1], values[2]);
    }
    return points;
}

} // namespace overlayd
