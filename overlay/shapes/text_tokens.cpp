// Token expansion for screen text, checked once at configure time so that the frame path cannot fail.
#include "overlay/shapes/text_tokens.h"

#include <chrono>
#include <cstdio>
#include <ctime>

namespace overlayd {

namespace {

// Calls emit(literal) for text and token(name) for each {name}; false on a syntax error.
template<typename Literal, typename Token>
bool scan(std::string_view text, Literal &&literal, Token &&token)
{
    size_t i = 0;
    while (i < text.size()) {
        const char c = text[i];
        if ((c == '{' || c == '}') && i + 1 < text.size() && text[i + 1] == c) {
            literal(text.substr(i, 1));
            i += 2;
        } else if (c == '{') {
            const size_t close = text.find('}', i);
            if (close == std::string_view::npos)
                return false;
            token(text.substr(i + 1, close - i - 1));
            i = close + 1;
        } else if (c == '}') {
            return false;
        } else {
            const size_t next = text.find_first_of("{}", i);
            const size_t end = next == std::string_view::npos ? text.size() : next;
            literal(text.substr(i, end - i));
            i = end;
        }
    }
    return true;
}

bool knownToken(std::string_view name)
{
    return name == "frame" || name == "fps" || name == "ms" || name.starts_with("time:");
}

void appendTime(std::string_view format, std::chrono::system_clock::time_point wallClock, std::string &out)
{
    const std::time_t seconds = std::chrono::system_clock::to_time_t(wallClock);
    std::tm local{};
    localtime_r(&seconds, &local);
    char pattern[128], buffer[256];
    const size_t length = std::min(format.size(), sizeof(pattern) - 1);
    format.copy(pattern, length);
    pattern[length] = '\0';
    const size_t written = std::strftime(buffer, sizeof(buffer), pattern, &local);
    out.append(buffer, written);
}

} // namespace

Status checkTokens(std::string_view text)
{
    std::string unknown;
    const bool ok = scan(
        text, [](std::string_view) {},
        [&](std::string_view name) {
            if (!knownToken(name) && unknown.empty())
                unknown = name;
        });
    if (!ok)
        return makeError(ErrorCode::InvalidArgument,
                         "unbalanced brace in text \"" + std::string(text) + "\" (write {{ and }} for literal braces)");
    if (!unknown.empty())
        return makeError(ErrorCode::InvalidArgument, "unknown token {" + unknown + "} in text \"" + std::string(text) +
                                                         "\" (known: frame, fps, ms, time:FORMAT)");
    return Ok{};
}

bool hasTokens(std::string_view text)
{
    bool any = false;
    scan(
        text, [](std::string_view) {}, [&](std::string_view) { any = true; });
    return any;
}

void expandTokens(std::string_view text, const FrameMetadata &metadata, double fps, std::string &out)
{
    out.clear();
    char number[32];
    scan(
        text, [&](std::string_view literal) { out.append(literal); },
        [&](std::string_view name) {
            if (name == "frame") {
                out.append(number, std::snprintf(number, sizeof(number), "%llu",
                                                 static_cast<unsigned long long>(metadata.sequence)));
            } else if (name == "fps") {
                out.append(number, std::snprintf(number, sizeof(number), "%.1f", fps));
            } else if (name == "ms") {
                const auto sinceEpoch = metadata.wallClock.time_since_epoch();
                const long long ms = std::chrono::duration_cast<std::chrono::milliseconds>(sinceEpoch).count() % 1000;
                out.append(number, std::snprintf(number, sizeof(number), "%03lld", (ms + 1000) % 1000));
            } else if (name.starts_with("time:")) {
                appendTime(name.substr(5), metadata.wallClock, out);
            }
        });
}

} // namespace overlayd
