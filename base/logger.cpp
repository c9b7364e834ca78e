// SPDX-License-Identifier: Apache-2.0
// Logger: formatting (journald priorities or local timestamps) and the repeat counter.
#include "base/logger.h"

#include <array>
#include <cstdio>
#include <cstdlib>
#include <ctime>

namespace overlayd {

namespace {

struct LevelInfo {
    LogLevel level;
    std::string_view name;
    int syslogPriority; // sd-daemon.h: SD_DEBUG 7 ... SD_ERR 3
};

constexpr std::array<LevelInfo, 5> kLevels{{
    {LogLevel::Debug, "debug", 7},
    {LogLevel::Info, "info", 6},
    {LogLevel::Notice, "notice", 5},
    {LogLevel::Warning, "warning", 4},
    {LogLevel::Error, "error", 3},
}};

const LevelInfo &levelInfo(LogLevel level)
{
    for (const LevelInfo &info : kLevels)
        if (info.level == level)
            return info;
    return kLevels[1];
}

std::string localTimestamp()
{
    const auto now = std::chrono::system_clock::now();
    const std::time_t seconds = std::chrono::system_clock::to_time_t(now);
    const auto millis = std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() % 1000;
    std::tm local{};
    localtime_r(&seconds, &local);
    char text[40];
    const size_t length = std::strftime(text, sizeof(text), "%Y-%m-%d %H:%M:%S", &local);
    std::snprintf(text + length, sizeof(text) - length, ".%03d", int(millis));
    return text;
}

} // namespace

std::string_view logLevelName(LogLevel level)
{
    return levelInfo(level).name;
}

bool parseLogLevel(std::string_view name, LogLevel &level)
{
    for (const LevelInfo &info : kLevels) {
        if (info.name == name) {
            level = info.level;
            return true;
        }
    }
    return false;
}

Logger::Logger(Writer writer, bool journal, Clock clock)
    : writer_(std::move(writer)), journal_(journal), clock_(std::move(clock))
{}

Logger Logger::forStderr()
{
    const char *journalStream = std::getenv("JOURNAL_STREAM");
    return Logger([](std::string_view line) { std::fwrite(line.data(), 1, line.size(), stderr); },
                  journalStream && *journalStream);
}

void Logger::setLevel(LogLevel level)
{
    std::lock_guard lock(mutex_);
    level_ = level;
}

LogLevel Logger::level() const
{
    std::lock_guard lock(mutex_);
    return level_;
}

void Logger::log(LogLevel level, std::string_view message)
{
    std::lock_guard lock(mutex_);
    if (level < level_)
        return;
    const auto now = clock_();
    if (message == last_ && level == lastLevel_ && now - lastPrinted_ < kRepeatWindow) {
        ++repeats_;
        return;
    }
    emitRepeats();
    emit(level, message);
    last_.assign(message);
    lastLevel_ = level;
    lastPrinted_ = now;
}

void Logger::flush()
{
    std::lock_guard lock(mutex_);
    emitRepeats();
}

void Logger::emitRepeats()
{
    if (repeats_ == 0)
        return;
    emit(lastLevel_, cat("last message repeated ", repeats_, " times"));
    repeats_ = 0;
}

void Logger::emit(LogLevel level, std::string_view message)
{
    const LevelInfo &info = levelInfo(level);
    std::string line;
    if (journal_)
        line = cat('<', info.syslogPriority, '>', message, '\n');
    else
        line = cat(localTimestamp(), ' ', info.name, ": ", message, '\n');
    writer_(line);
}

} // namespace overlayd
