// SPDX-License-Identifier: Apache-2.0
// parseJsonBody: nlohmann's exceptions become a Malformed error; writeJson: nlohmann never throws for bad text.
#include "config/json_body.h"

namespace overlayd {

Result<nlohmann::json> parseJsonBody(std::string_view text)
{
    try {
        return nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception &error) {
        // Without the library's tag: "[json.exception.parse_error.101] parse error at line 1, column 2: ..." says
        // "at line 1, column 2: ...".
        std::string why = error.what();
        if (const size_t tag = why.find("] "); why.rfind("[json.exception.", 0) == 0 && tag != std::string::npos)
            why.erase(0, tag + 2);
        if (why.rfind("parse error ", 0) == 0)
            why.erase(0, std::string_view("parse error ").size());
        return makeError(ErrorCode::Malformed, "the body is not JSON: " + why);
    }
}

std::string writeJson(const nlohmann::json &value)
{
    return value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

} // namespace overlayd
