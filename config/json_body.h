// SPDX-License-Identifier: Apache-2.0
// An HTTP request body read as JSON and an answer's JSON written: the one place each is done, for the camera
// request here and the daemon's other routes.
#pragma once

#include <string_view>

#include <nlohmann/json.hpp>

#include "base/result.h"

namespace overlayd {

// Malformed ("the body is not JSON: ...") for text that does not parse, a number beyond double included (nlohmann
// throws out_of_range for it, not parse_error: found by tests/fuzz/http_api_fuzz). Never throws.
Result<nlohmann::json> parseJsonBody(std::string_view text);
// value as JSON text. A string that is not valid UTF-8 is written with U+FFFD in place of its bad bytes instead of
// throwing (nlohmann's default): outside text is checked where it enters, this is the second line of defence.
std::string writeJson(const nlohmann::json &value);

} // namespace overlayd
