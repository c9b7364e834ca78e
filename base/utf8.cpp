// SPDX-License-Identifier: Apache-2.0
// A table-free strict decoder: the second byte's range depends on the first (RFC 3629 section 4), which is what
// refuses overlong forms (C0, C1, E0 80-9F, F0 80-8F), surrogates (ED A0-BF) and code points above U+10FFFF
// (F4 90-BF, F5-FF).
#include "base/utf8.h"

#include <algorithm>
#include <cstdio>

namespace overlayd {

namespace {

struct Lead {
    size_t length;           // bytes in the sequence
    unsigned char second[2]; // the second byte's range
};

Lead leadOf(unsigned char byte)
{
    if (byte < 0x80)
        return {1, {0, 0}};
    if (byte >= 0xC2 && byte <= 0xDF)
        return {2, {0x80, 0xBF}};
    if (byte == 0xE0)
        return {3, {0xA0, 0xBF}};
    if (byte == 0xED)
        return {3, {0x80, 0x9F}};
    if (byte >= 0xE1 && byte <= 0xEF)
        return {3, {0x80, 0xBF}};
    if (byte == 0xF0)
        return {4, {0x90, 0xBF}};
    if (byte >= 0xF1 && byte <= 0xF3)
        return {4, {0x80, 0xBF}};
    if (byte == 0xF4)
        return {4, {0x80, 0x8F}};
    return {0, {0, 0}}; // a continuation byte, C0, C1 or F5-FF
}

unsigned char byteAt(std::string_view text, size_t at)
{
    return static_cast<unsigned char>(text[at]);
}

// The code point of the valid sequence of `length` bytes at text[at].
char32_t decode(std::string_view text, size_t at, size_t length)
{
    static constexpr unsigned char kLeadMask[] = {0, 0x7F, 0x1F, 0x0F, 0x07};
    char32_t codePoint = byteAt(text, at) & kLeadMask[length];
    for (size_t i = 1; i < length; ++i)
        codePoint = (codePoint << 6) | (byteAt(text, at + i) & 0x3F);
    return codePoint;
}

} // namespace

size_t utf8SequenceLength(std::string_view text, size_t at)
{
    if (at >= text.size())
        return 0;
    const Lead lead = leadOf(byteAt(text, at));
    if (lead.length <= 1)
        return lead.length;
    if (text.size() - at < lead.length)
        return 0;
    const unsigned char second = byteAt(text, at + 1);
    if (second < lead.second[0] || second > lead.second[1])
        return 0;
    for (size_t i = 2; i < lead.length; ++i)
        if ((byteAt(text, at + i) & 0xC0) != 0x80)
            return 0;
    return lead.length;
}

size_t validUtf8Prefix(std::string_view text)
{
    size_t at = 0;
    while (at < text.size()) {
        const size_t length = utf8SequenceLength(text, at);
        if (length == 0)
            break;
        at += length;
    }
    return at;
}

bool isControlCharacter(char32_t codePoint)
{
    return codePoint < 0x20 || (codePoint >= 0x7F && codePoint <= 0x9F);
}

size_t utf8Cut(std::string_view text, size_t maxBytes)
{
    if (text.size() <= maxBytes)
        return text.size();
    size_t cut = maxBytes;
    while (cut > 0 && (byteAt(text, cut) & 0xC0) == 0x80)
        --cut; // text[cut] continues the character before it
    return cut;
}

std::optional<std::string> outsideTextProblem(std::string_view text, std::string_view allowed)
{
    for (size_t at = 0; at < text.size();) {
        const size_t length = utf8SequenceLength(text, at);
        if (length == 0)
            return "not valid UTF-8 at byte " + std::to_string(at);
        const char32_t codePoint = decode(text, at, length);
        if (isControlCharacter(codePoint) && (length > 1 || allowed.find(text[at]) == std::string_view::npos)) {
            char name[16];
            std::snprintf(name, sizeof(name), "U+%04X", unsigned(codePoint));
            return std::string("a control character (") + name + ") at byte " + std::to_string(at);
        }
        at += length;
    }
    return std::nullopt;
}

std::string quotable(std::string_view text, size_t maxBytes)
{
    const size_t cut = utf8Cut(text, maxBytes);
    std::string out;
    for (size_t at = 0; at < cut;) {
        const size_t length = utf8SequenceLength(text.substr(0, cut), at);
        if (length == 0 || isControlCharacter(decode(text, at, length))) {
            for (size_t i = 0; i < std::max<size_t>(length, 1); ++i) {
                char escaped[8];
                std::snprintf(escaped, sizeof(escaped), "\\x%02X", unsigned(byteAt(text, at + i)));
                out += escaped;
            }
            at += std::max<size_t>(length, 1);
            continue;
        }
        out.append(text, at, length);
        at += length;
    }
    return cut < text.size() ? out + "..." : out;
}

} // namespace overlayd
