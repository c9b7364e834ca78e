// SPDX-License-Identifier: Apache-2.0
// Token expansion for screen text, checked once at configure time so that the frame path cannot fail.
#include "overlay/shapes/text_tokens.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <ctime>

#include "base/utf8.h"

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

constexpr std::string_view kSlotPrefix = "slot:";

// A slot name as the control path and the config spell it: letters, digits, '_', '-' and '.'.
bool validSlotName(std::string_view name)
{
    if (name.empty() || name.size() > 64)
        return false;
    for (const char c : name)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-' && c != '.')
            return false;
    return true;
}

bool knownToken(std::string_view name)
{
    if (name.starts_with(kSlotPrefix))
        return validSlotName(name.substr(kSlotPrefix.size()));
    return name == "frame" || name == "fps" || name == "ms" || name == "exposure" || name == "gain" ||
           name.starts_with("time:");
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
        return makeError(ErrorCode::InvalidArgument,
                         "unknown token {" + unknown + "} in text \"" + std::string(text) +
                             "\" (known: frame, fps, ms, exposure, gain, time:FORMAT, slot:NAME)");
    return Ok{};
}

bool hasTokens(std::string_view text)
{
    bool any = false;
    scan(
        text, [](std::string_view) {}, [&](std::string_view) { any = true; });
    return any;
}

void appendSlotNames(std::string_view text, std::vector<std::string> &names)
{
    scan(
        text, [](std::string_view) {},
        [&](std::string_view name) {
            if (!name.starts_with(kSlotPrefix))
                return;
            const std::string slot(name.substr(kSlotPrefix.size()));
            if (std::find(names.begin(), names.end(), slot) == names.end())
                names.push_back(slot);
        });
}

Status checkSlotText(std::string_view text)
{
    if (text.size() > kMaxSlotTextBytes)
        return makeError(ErrorCode::InvalidArgument, "slot text of " + std::to_string(text.size()) +
                                                         " bytes: at most " + std::to_string(kMaxSlotTextBytes));
    // Slot text comes from outside (files, the API, CAN): /state quotes it as JSON, the renderer draws it.
    if (const auto problem = outsideTextProblem(text))
        return makeError(ErrorCode::InvalidArgument, "slot text is not one line of UTF-8 text: " + *problem);
    return Ok{};
}

void expandTokens(std::string_view text, const FrameMetadata &metadata, double fps, std::string &out,
                  const SlotTexts *slots)
{
    out.clear();
    // Room for any number printed here, whole: "%.2f" of the largest double is 313 characters (a camera's gain is
    // its driver's float). On the stack, as nothing on the frame path allocates once the text has grown.
    char number[320];
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
            } else if (name == "exposure") {
                // Microseconds, as the camera reports them; "-" when the source reports none.
                if (metadata.exposureUs)
                    out.append(number, std::snprintf(number, sizeof(number), "%d", int(*metadata.exposureUs)));
                else
                    out.append("-");
            } else if (name == "gain") {
                if (metadata.analogueGain)
                    out.append(number, std::snprintf(number, sizeof(number), "%.2f", double(*metadata.analogueGain)));
                else
                    out.append("-");
            } else if (name.starts_with("time:")) {
                appendTime(name.substr(5), metadata.wallClock, out);
            } else if (name.starts_with(kSlotPrefix) && slots) {
                if (const auto found = slots->find(name.substr(kSlotPrefix.size())); found != slots->end())
                    out.append(found->second);
            }
        });
}

} // namespace overlayd
