// jsonString: the escapes RFC 8259 requires (quote, backslash, control characters); UTF-8 passes through.
#include "base/json_text.h"

#include "base/number_text.h"

#include <charconv>
#include <cmath>
#include <cstdio>

namespace overlayd {

std::string jsonString(const std::string &text)
{
    std::string out = "\"";
    for (const char c : text) {
        if (c == '"' || c == '\\') {
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
