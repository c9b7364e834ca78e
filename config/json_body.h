// An HTTP request body read as JSON: the one place its text is parsed, for the camera request here and the
// daemon's other routes.
#pragma once

#include <string_view>

#include <nlohmann/json.hpp>

#include "base/result.h"

namespace overlayd {

// Malformed ("the body is not JSON: ...") for text that does not parse, a number beyond double included (nlohmann
// throws out_of_range for it, not parse_error: found by tests/fuzz/http_api_fuzz). Never throws.
Result<nlohmann::json> parseJsonBody(std::string_view text);

} // namespace overlayd
