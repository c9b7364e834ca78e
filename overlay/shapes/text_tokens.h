// SPDX-License-Identifier: Apache-2.0
// Screen-text tokens: {frame}, {fps}, {time:FORMAT}, {ms}, {slot:NAME} (text set at run time through the daemon's
// control path), and {{ / }} for literal braces.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "base/result.h"
#include "media/stream.h"

namespace overlayd {

// Refuses unknown tokens and unbalanced braces, naming the offending text.
Status checkTokens(std::string_view text);
// True when the text holds a token (its rendering can change from frame to frame).
bool hasTokens(std::string_view text);

// What each text slot shows now, by name; a slot never set shows nothing.
using SlotTexts = std::map<std::string, std::string, std::less<>>;
// The longest text a slot takes (a status line, a reading, a short message).
inline constexpr size_t kMaxSlotTextBytes = 256;

// The slot names a text's {slot:NAME} tokens use, appended to `names` once each.
void appendSlotNames(std::string_view text, std::vector<std::string> &names);
// What a slot may show: at most kMaxSlotTextBytes of valid UTF-8, printable (no control characters: one line of text).
Status checkSlotText(std::string_view text);

// Expands into `out` (cleared first; its capacity is reused). {time:FORMAT} formats the frame's wall clock in
// local time with strftime; {ms} is its milliseconds (000-999); {frame} the sequence number; {fps} one decimal;
// {slot:NAME} the slot's text from `slots` (nothing when absent).
void expandTokens(std::string_view text, const FrameMetadata &metadata, double fps, std::string &out,
                  const SlotTexts *slots = nullptr);

} // namespace overlayd
