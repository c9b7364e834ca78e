// What [http] asks for: where to listen, how many clients, how fast and how good the stream is, and who may change
// the scene. Compared whole (defaulted ==), so that a reload restarts the server only when [http] changed.
#pragma once

#include <string>

namespace overlayd {

// Limits, each named where it is enforced.
inline constexpr unsigned kMaxClients = 1024;               // connections at once (each holds an fd)
inline constexpr double kMaxStreamFps = 120.0;              // per-client cap of /stream
inline constexpr size_t kMaxBodyBytes = 64 * 1024;          // a control request's body (413 beyond)
inline constexpr size_t kMaxUrlBytes = 8 * 1024;            // path and query (414 beyond)
inline constexpr size_t kConnectionMemoryBytes = 32 * 1024; // libmicrohttpd's per-connection pool: all headers
inline constexpr unsigned kIdleTimeoutSec = 10;             // a connection that sends or reads nothing is closed
inline constexpr size_t kMaxTokenBytes = 256;

enum class ControlMode {
    Off,   // the control API answers 403
    Token, // the control API needs "Authorization: Bearer TOKEN"
    Open,  // anyone who can connect may control: only on loopback or a unix socket
};

struct HttpOptions {
    bool enabled = false; // an [http] table was given
    std::string listen = "127.0.0.1:8080";
    unsigned maxClients = 32;
    double streamFps = 15.0;
    int jpegQuality = 80;
    ControlMode control = ControlMode::Token;
    std::string tokenFile;     // absolute (resolved against the config's folder)
    std::string pageDirectory; // the alignment page's files; empty: the installed default
    bool operator==(const HttpOptions &) const = default;
};

// Whether this overlayd has the server (CMake option OVERLAYD_HTTP, libmicrohttpd): without it the config refuses
// [http] at load, so check-config says what run could not do. Defined by http_server.cpp or http_server_none.cpp.
bool httpBuiltIn();

} // namespace overlayd