// SPDX-License-Identifier: Apache-2.0
// What a user can configure about a push: one [[sink]] kind = "push", the encoded stream published to a server.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace overlayd {

// The protocols a push speaks, each by its URL scheme: RTSP ANNOUNCE/RECORD, RTMP publish, SRT caller.
enum class PushProtocol { Rtsp, Rtmp, Srt };

inline constexpr size_t kMaxPushUrlBytes = 2048; // url (docs/config.md "Limits")

struct PushSinkOptions {
    std::string url;
    PushProtocol protocol = PushProtocol::Rtsp; // from the URL's scheme

    bool operator==(const PushSinkOptions &) const = default;
};

// The protocol of a push URL: rtsp://, rtmp:// or srt:// followed by a host. Anything else is nullopt with the
// reason in `why` (the scheme it has, or what is missing).
std::optional<PushProtocol> pushProtocol(std::string_view url, std::string &why);
std::string_view protocolName(PushProtocol protocol); // "rtsp", "rtmp", "srt"

} // namespace overlayd
