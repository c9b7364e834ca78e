// parseJsonBody: nlohmann's exceptions become a Malformed error.
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

} // namespace overlayd
