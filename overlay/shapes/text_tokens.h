// Screen-text tokens: {frame}, {fps}, {time:FORMAT}, {ms}, and {{ / }} for literal braces.
#pragma once

#include <string>
#include <string_view>

#include "base/result.h"
#include "media/stream.h"

namespace overlayd {

// Refuses unknown tokens and unbalanced braces, naming the offending text.
Status checkTokens(std::string_view text);
// True when the text holds a token (its rendering can change from frame to frame).
bool hasTokens(std::string_view text);

// Expands into `out` (cleared first; its capacity is reused). {time:FORMAT} formats the frame's wall clock in
// local time with strftime; {ms} is its milliseconds (000-999); {frame} the sequence number; {fps} one decimal.
void expandTokens(std::string_view text, const FrameMetadata &metadata, double fps, std::string &out);

} // namespace overlayd
