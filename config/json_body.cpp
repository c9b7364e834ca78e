// parseJsonBody: nlohmann's exceptions become a Malformed error; writeJson: nlohmann never throws for bad text.
#include "config/json_body.h"

namespace overlayd {

Result<nlohmann::json> parseJsonBody(std::string_view text)
{
    try {
        return nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception &error) {
        return makeError(ErrorCode::Malformed, std::string("the body is not JSON: ") + error.what());
    }
}

std::string writeJson(const nlohmann::json &value)
{
    return value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

} // namespace overlayd
