// SPDX-License-Identifier: Apache-2.0
// Who may watch an RTSP sink and over what: the sink's `auth` and `tls` keys as written, and what the config loader
// resolved them to from [http] (its users, tokens and certificate), so that the engine's module, which reads no
// files of the project's, gets the secrets as data.
#pragma once

#include <string>
#include <vector>

namespace overlayd {

enum class RtspAuth {
    Http,       // as [http] viewer: a credential when it is "credential", none when "open" (or no [http])
    Credential, // always a credential of [http] (refused when [http] has none)
    None,       // anyone who can connect
};

enum class RtspTls {
    Http, // RTSPS with [http]'s certificate when it has one, else plain RTSP
    Off,  // plain RTSP even when [http] serves HTTPS
};

// An RTSP basic user: a users_file user (viewer or control), or kRtspTokenUser with a token as its password.
struct RtspUser {
    std::string name, password;
    bool operator==(const RtspUser &) const = default;
};

// The user name under which [http]'s viewer and control tokens are accepted as passwords.
inline constexpr const char *kRtspTokenUser = "token";

struct RtspAccessOptions {
    RtspAuth auth = RtspAuth::Http;
    RtspTls tls = RtspTls::Http;
    std::vector<RtspUser> users; // resolved: empty means no credential is asked
    std::string certPem, keyPem; // resolved: empty means plain RTSP

    bool operator==(const RtspAccessOptions &) const = default;
};

} // namespace overlayd
