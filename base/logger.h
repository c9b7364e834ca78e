// SPDX-License-Identifier: Apache-2.0
// Logger: the daemon's log lines on stderr, with syslog priority prefixes under journald and rate-limited repeats.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <mutex>
#include <sstream>
#include <string>
#include <string_view>

namespace overlayd {

enum class LogLevel { Debug, Info, Notice, Warning, Error };

std::string_view logLevelName(LogLevel level);
// "debug" | "info" | "notice" | "warning" | "error"; false for anything else.
bool parseLogLevel(std::string_view name, LogLevel &level);

// Concatenates anything streamable: cat("frame ", 12, " dropped").
template<typename... Args>
std::string cat(const Args &...args)
{
    std::ostringstream out;
    (out << ... << args);
    return out.str();
}

class Logger
{
public:
    using Writer = std::function<void(std::string_view line)>; // one whole line, with its newline
    using Clock = std::function<std::chrono::steady_clock::time_point()>;

    // Identical consecutive messages within this window are counted instead of printed.
    static constexpr std::chrono::seconds kRepeatWindow{10};

    // journal: prefix "<N>" priorities (journald parses them) instead of timestamps.
    Logger(Writer writer, bool journal, Clock clock = &std::chrono::steady_clock::now);
    // Writes to stderr; journald style when JOURNAL_STREAM is set (systemd sets it for the service's stderr).
    static Logger forStderr();

    void setLevel(LogLevel level);
    LogLevel level() const;
    // Thread-safe: sink workers log too.
    void log(LogLevel level, std::string_view message);
    // Prints a pending "repeated N times" line (at shutdown).
    void flush();

    void debug(std::string_view message) { log(LogLevel::Debug, message); }
    void info(std::string_view message) { log(LogLevel::Info, message); }
    void notice(std::string_view message) { log(LogLevel::Notice, message); }
    void warning(std::string_view message) { log(LogLevel::Warning, message); }
    void error(std::string_view message) { log(LogLevel::Error, message); }

private:
    void emit(LogLevel level, std::string_view message);
    void emitRepeats();

    Writer writer_;
    bool journal_;
    Clock clock_;
    mutable std::mutex mutex_;
    LogLevel level_ = LogLevel::Info;
    std::string last_;
    LogLevel lastLevel_ = LogLevel::Info;
    std::chrono::steady_clock::time_point lastPrinted_{};
    uint64_t repeats_ = 0;
};

} // namespace overlayd
