// SPDX-License-Identifier: Apache-2.0
// Segment names to and from UTC times, through gmtime_r/timegm (no time zone, no locale).
#include "stream/segment_name.h"

#include <cstdio>
#include <ctime>

namespace overlayd {

namespace {

constexpr size_t kStampLength = 16; // "YYYYMMDDTHHMMSSZ"

// The digits of [at, at + count) as a number, or -1 when one is not a digit.
int digits(std::string_view text, size_t at, size_t count)
{
    int value = 0;
    for (size_t i = at; i < at + count; ++i) {
        if (text[i] < '0' || text[i] > '9')
            return -1;
        value = value * 10 + (text[i] - '0');
    }
    return value;
}

std::optional<WallClock::time_point> parseStamp(std::string_view stamp)
{
    if (stamp.size() != kStampLength || stamp[8] != 'T' || stamp[15] != 'Z')
        return std::nullopt;
    std::tm tm{};
    tm.tm_year = digits(stamp, 0, 4) - 1900;
    tm.tm_mon = digits(stamp, 4, 2) - 1;
    tm.tm_mday = digits(stamp, 6, 2);
    tm.tm_hour = digits(stamp, 9, 2);
    tm.tm_min = digits(stamp, 11, 2);
    tm.tm_sec = digits(stamp, 13, 2);
    const std::tm asRead = tm;
    const time_t seconds = timegm(&tm);
    // timegm normalizes a 31st of November into December: such a name was not written by us.
    if (seconds == time_t(-1) || tm.tm_year != asRead.tm_year || tm.tm_mon != asRead.tm_mon ||
        tm.tm_mday != asRead.tm_mday || tm.tm_hour != asRead.tm_hour || tm.tm_min != asRead.tm_min ||
        tm.tm_sec != asRead.tm_sec)
        return std::nullopt;
    return WallClock::from_time_t(seconds);
}

} // namespace

std::string segmentFileName(WallClock::time_point start, std::string_view extension, unsigned repeat)
{
    const time_t seconds = WallClock::to_time_t(std::chrono::floor<std::chrono::seconds>(start));
    std::tm tm{};
    gmtime_r(&seconds, &tm);
    char stamp[64]; // room for any int year, which the compiler cannot rule out
    std::snprintf(stamp, sizeof(stamp), "%04d%02d%02dT%02d%02d%02dZ", tm.tm_year + 1900, tm.tm_mon + 1, tm.tm_mday,
                  tm.tm_hour, tm.tm_min, tm.tm_sec);
    std::string name(stamp);
    if (repeat > 0)
        name += "-" + std::to_string(repeat);
    return name + "." + std::string(extension);
}

std::string partialFileName(std::string_view finalName)
{
    return std::string(finalName) + std::string(kPartialSuffix);
}

std::optional<SegmentFile> parseSegmentFileName(std::string_view name, std::string_view extension)
{
    SegmentFile file;
    if (name.ends_with(kPartialSuffix)) {
        file.partial = true;
        name.remove_suffix(kPartialSuffix.size());
    }
    file.finalName = std::string(name);
    const std::string dotExtension = "." + std::string(extension);
    if (!name.ends_with(dotExtension) || name.size() < kStampLength + dotExtension.size())
        return std::nullopt;
    name.remove_suffix(dotExtension.size());
    const std::string_view repeat = name.substr(kStampLength);
    // At most nine digits: an int holds them.
    if (!repeat.empty() &&
        (repeat.size() < 2 || repeat.size() > 10 || repeat.front() != '-' || digits(repeat, 1, repeat.size() - 1) < 0))
        return std::nullopt;
    file.repeat = repeat.empty() ? 0 : unsigned(digits(repeat, 1, repeat.size() - 1));
    const auto start = parseStamp(name.substr(0, kStampLength));
    if (!start)
        return std::nullopt;
    file.start = *start;
    return file;
}

} // namespace overlayd
