// SPDX-License-Identifier: Apache-2.0
// An RTSP sink's `auth` and `tls` keys, and what they resolve to once [http] is read: its basic users and tokens
// as RTSP basic users, its certificate and key for RTSPS.
#include "config/config_sections.h"

#include "http/credentials.h"
#include "http/token_file.h"
#include "stream/engine_loader.h"

namespace overlayd {

void readRtspAccess(TableReader &sink, RtspAccessOptions &out)
{
    if (auto auth = sink.choice<RtspAuth>(
            "auth", {{"http", RtspAuth::Http}, {"credential", RtspAuth::Credential}, {"none", RtspAuth::None}}))
        out.auth = *auth;
    if (auto tls = sink.choice<RtspTls>("tls", {{"http", RtspTls::Http}, {"off", RtspTls::Off}}))
        out.tls = *tls;
}

namespace {

// Every credential that may watch on [http]: its users (viewer and control alike) and its tokens under
// kRtspTokenUser. The files were checked by readHttp, which reported any it could not read.
std::vector<RtspUser> httpViewers(const HttpOptions &http)
{
    std::vector<RtspUser> out;
    if (!http.usersFile.empty())
        if (auto users = readUsersFile(http.usersFile))
            for (const BasicUser &user : *users)
                out.push_back({user.name, user.password});
    const bool controlToken = http.control == ControlMode::Token;
    for (const std::string &file : {controlToken ? http.tokenFile : std::string(), http.viewerTokenFile})
        if (!file.empty())
            if (auto token = readTokenFile(file))
                out.push_back({kRtspTokenUser, *token});
    return out;
}

} // namespace

void resolveRtspAccess(TableReader &root, const HttpOptions &http, StreamOptions &stream)
{
    for (EncodedSinkOptions &sink : stream.sinks) {
        if (sink.kind != EncodedSinkKind::Rtsp)
            continue;
        RtspAccessOptions &access = sink.rtsp.access;
        const bool needsCredential =
            access.auth == RtspAuth::Credential || (access.auth == RtspAuth::Http && http.enabled && !http.viewerOpen);
        access.users = needsCredential ? httpViewers(http) : std::vector<RtspUser>{};
        if (needsCredential && access.users.empty())
            root.problemAtPath(sink.key + ".auth",
                               "\"credential\" needs a credential in [http] (users_file, viewer_token_file or "
                               "token_file): without one nobody could watch");
        if (access.tls == RtspTls::Http && http.enabled)
            access.certPem = http.tls.certPem, access.keyPem = http.tls.keyPem;
        if (!access.certPem.empty())
            if (auto served = checkRtspsCertificate(access.certPem, access.keyPem); !served)
                root.problemAtPath(sink.key + ".tls",
                                   served.error().message + " (tls = \"off\" serves plain RTSP beside [http]'s HTTPS)");
    }
}

} // namespace overlayd
