// SPDX-License-Identifier: Apache-2.0
// percentDecoded: RFC 3986 section 2.1, with the control characters refused rather than passed on.
#include "http/percent_decoding.h"

namespace overlayd {

namespace {

int hexValue(char c)
{
    if (c >= '0' && c <= '9')
        return c - '0';
    if (c >= 'a' && c <= 'f')
        return c - 'a' + 10;
    if (c >= 'A' && c <= 'F')
        return c - 'A' + 10;
    return -1;
}

} // namespace

Result<std::string> percentDecoded(std::string_view text)
{
    std::string out;
    out.reserve(text.size());
    for (size_t i = 0; i < text.size(); ++i) {
        unsigned char byte = static_cast<unsigned char>(text[i]);
        if (byte == '%') {
            const int high = i + 2 < text.size() ? hexValue(text[i + 1]) : -1;
            const int low = high >= 0 ? hexValue(text[i + 2]) : -1;
            if (low < 0)
                return makeError(ErrorCode::InvalidArgument, "a '%' not followed by two hex digits");
            byte = static_cast<unsigned char>(high * 16 + low);
            i += 2;
        }
        if (byte < 0x20 || byte == 0x7f)
            return makeError(ErrorCode::InvalidArgument,
                             "a control character (byte " + std::to_string(unsigned(byte)) + ") is in no name");
        out += static_cast<char>(byte);
    }
    return out;
}

} // namespace overlayd
