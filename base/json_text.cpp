// SPDX-License-Identifier: Apache-2.0
// jsonString: the escapes RFC 8259 requires (quote, backslash, control characters); valid UTF-8 passes through, and
// each byte that is not (a device's card name, a file name) becomes U+FFFD, so the output is always JSON.
#include "base/json_text.h"

#include "base/number_text.h"
#include "base/utf8.h"

#include <charconv>
#include <cmath>
#include <cstdio>

namespace overlayd {

std::string jsonString(const std::string &text)
{
    std::string out = "\"";
    for (size_t at = 0; at < text.size();) {
        const char c = text[at];
        const size_t length = utf8SequenceLength(text, at);
        if (length > 1) {
            out.append(text, at, length);
            at += length;
            continue;
        }
        ++at;
        if (length == 0) {
            out += "\\ufffd"; // the JSON escape of U+FFFD, the replacement character
        } else if (c == '"' || c == '\\') {
            out += '\\';
            out += c;
        } else if (static_cast<unsigned char>(c) < 0x20) {
            out += formatted("\\u%04x", unsigned(c));
        } else {
            out += c;
        }
    }
    return out + "\"";
}

std::string jsonNumber(double value)
{
    if (!std::isfinite(value))
        return "null";
    char text[32]; // the shortest round-trip form of any double is at most 24 characters (-2.2250738585072014e-308)
    const auto result = std::to_chars(text, text + sizeof(text), value);
    return std::string(text, result.ptr);
}

} // namespace overlayd
