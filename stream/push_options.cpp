// SPDX-License-Identifier: Apache-2.0
// Push URLs: the scheme picks the protocol; a host must follow it.
#include "stream/push_options.h"

#include <array>
#include <utility>

namespace overlayd {

namespace {

constexpr std::array<std::pair<std::string_view, PushProtocol>, 3> kSchemes = {{
    {"rtsp", PushProtocol::Rtsp},
    {"rtmp", PushProtocol::Rtmp},
    {"srt", PushProtocol::Srt},
}};

} // namespace

std::optional<PushProtocol> pushProtocol(std::string_view url, std::string &why)
{
    const size_t colon = url.find("://");
    if (colon == std::string_view::npos) {
        why = "not a URL: expected rtsp://, rtmp:// or srt:// and a host";
        return std::nullopt;
    }
    const std::string_view scheme = url.substr(0, colon);
    const std::string_view rest = url.substr(colon + 3);
    for (const auto &[name, protocol] : kSchemes) {
        if (scheme != name)
            continue;
        // The host ends at the port, the path or the query; an empty one leaves the element nothing to reach.
        if (rest.empty() || rest.front() == ':' || rest.front() == '/' || rest.front() == '?') {
            why = "no host after " + std::string(scheme) + "://";
            return std::nullopt;
        }
        return protocol;
    }
    why = "the scheme '" + std::string(scheme) + "' cannot be pushed to: rtsp://, rtmp:// or srt://";
    return std::nullopt;
}

std::string_view protocolName(PushProtocol protocol)
{
    for (const auto &[name, value] : kSchemes)
        if (value == protocol)
            return name;
    return "?";
}

} // namespace overlayd
