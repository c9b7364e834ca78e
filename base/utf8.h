// SPDX-License-Identifier: Apache-2.0
// Outside text (files other programs write, API bodies, config strings) checked against one policy: strict UTF-8
// (RFC 3629: no overlong forms, no surrogates, nothing above U+10FFFF) and no control characters but those a
// format needs. Text that breaks it is refused where it enters; what quotes it in a message makes it safe first.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace overlayd {

// The length of the valid UTF-8 sequence starting at text[at], 0 when the bytes there are not one.
size_t utf8SequenceLength(std::string_view text, size_t at);
// The length of text's longest valid UTF-8 prefix: text.size() when the whole text is valid.
size_t validUtf8Prefix(std::string_view text);
inline bool isValidUtf8(std::string_view text)
{
    return validUtf8Prefix(text) == text.size();
}
// C0 (U+0000-U+001F), DEL (U+007F) and C1 (U+0080-U+009F, two bytes C2 80-9F): never drawn, never shown.
bool isControlCharacter(char32_t codePoint);
// The longest prefix of at most maxBytes bytes that does not end inside a UTF-8 sequence.
size_t utf8Cut(std::string_view text, size_t maxBytes);
// What is wrong with outside text: "not valid UTF-8 at byte N" or "a control character (U+000D) at byte N";
// nullopt when it keeps the policy. allowed: the control characters the format needs (e.g. "\t").
std::optional<std::string> outsideTextProblem(std::string_view text, std::string_view allowed = {});
// Text a message may quote: at most maxBytes of it cut on a character boundary ("..." added when cut), each byte
// that is not valid UTF-8 and each control character written as \xNN. Always valid UTF-8.
std::string quotable(std::string_view text, size_t maxBytes);

} // namespace overlayd
