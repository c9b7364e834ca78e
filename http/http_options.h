// SPDX-License-Identifier: Apache-2.0
// What [http] asks for: where to listen, how many clients, how fast and how good the stream is, and who may change
// the scene. Compared whole (defaulted ==), so that a reload restarts the server only when [http] changed.
#pragma once

#include <string>

#include "http/tls_files.h"

namespace overlayd {

// Limits, each named where it is enforced.
inline constexpr unsigned kMaxClients = 1024;               // connections at once (each holds an fd)
inline constexpr double kMaxStreamFps = 120.0;              // per-client cap of /stream
inline constexpr size_t kMaxBodyBytes = 64 * 1024;          // a control request's body (413 beyond)
inline constexpr size_t kMaxUrlBytes = 8 * 1024;            // path and query (414 beyond)
inline constexpr size_t kConnectionMemoryBytes = 32 * 1024; // libmicrohttpd's per-connection pool: all headers
inline constexpr unsigned kIdleTimeoutSec = 10;             // a connection that sends or reads nothing is closed
inline constexpr size_t kMaxTokenBytes = 256;
// Hostile clients (http/request_slots.h): fixed deadlines from a request's first byte, which trickling bytes do not
// extend, and caps on the requests still arriving.
inline constexpr unsigned kHeaderDeadlineSec = 10;   // the request line and headers complete within this
inline constexpr unsigned kBodyDeadlineSec = 20;     // then the body (at most kMaxBodyBytes) within this
inline constexpr unsigned kMaxPendingPerAddress = 8; // default of max_pending_per_address
inline constexpr unsigned kSpareConnections = 4;     // accepted over max_clients, so a new request always gets in
inline constexpr unsigned kKeptForRequests = 4;      // max_streams' default leaves this many slots to requests
inline constexpr int kListenBacklog = 1024;          // connections the kernel queues before the server accepts them
// Credentials (http/credentials.h; the refusals' limits are base/auth_failures.h's).
inline constexpr size_t kMaxUsers = 64; // users in users_file
// users_file users may answer a Digest challenge (MD5, RFC 2617/7616) instead of sending Basic: its nonce is good
// for kDigestNonceSec (then "stale": the client answers a fresh one without asking its user), and libmicrohttpd
// remembers the counts of the last kDigestNonces nonces, so a replayed answer is refused.
inline constexpr unsigned kDigestNonceSec = 300;
inline constexpr unsigned kDigestNonces = 1024;
inline constexpr const char *kAuthRealm = "overlayd"; // Basic's and Digest's, and the RTSP sinks' too

enum class ControlMode {
    Off,   // the control API answers 403
    Token, // the control API needs "Authorization: Bearer TOKEN"
    Open,  // anyone who can connect may control: only on loopback or a unix socket
};

struct HttpOptions {
    bool enabled = false; // an [http] table was given
    std::string listen = "127.0.0.1:8080";
    unsigned maxClients = 32;
    unsigned maxStreams = 0;                               // 0: max_clients - kKeptForRequests (at least 1)
    unsigned maxPendingPerAddress = kMaxPendingPerAddress; // incomplete requests from one client address
    double streamFps = 15.0;
    int jpegQuality = 80;
    ControlMode control = ControlMode::Token;
    std::string tokenFile;       // absolute (resolved against the config's folder)
    std::string viewerTokenFile; // the viewer token (absolute); empty: none
    std::string usersFile;       // HTTP basic users (absolute); empty: none
    bool viewerOpen = true;      // watching needs no credential (viewer = "open")
    std::string pageDirectory;   // the alignment page's files; empty: the installed default
    std::string tlsCert, tlsKey; // absolute; both or neither (HTTPS)
    TlsFiles tls;                // their contents: a renewed certificate changes the options, and a reload swaps it in
    bool operator==(const HttpOptions &) const = default;
};

// Whether this overlayd has the server (CMake option OVERLAYD_HTTP, libmicrohttpd): without it the config refuses
// [http] at load, so check-config says what run could not do. Defined by http_server.cpp or http_server_none.cpp.
bool httpBuiltIn();

} // namespace overlayd
