// SPDX-License-Identifier: Apache-2.0
// A request's path and query, %-decoded by us and not by libmicrohttpd: its decoder writes a decoded NUL into a C
// string, so "/api/layers/a%00b" reached the API as "/api/layers/a" and changed another layer.
#pragma once

#include <string>
#include <string_view>

#include "base/result.h"

namespace overlayd {

// The text with each %XX replaced by its byte. InvalidArgument for a '%' without two hex digits after it, and for a
// control character (U+0000..U+001F, U+007F), written raw or %-escaped: no name, slot or number holds one.
Result<std::string> percentDecoded(std::string_view text);

} // namespace overlayd
