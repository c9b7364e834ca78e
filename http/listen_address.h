// SPDX-License-Identifier: Apache-2.0
// Where the server listens: "HOST:PORT" (IPv4 dotted quad, "[IPv6]", or "localhost") or "unix:/path".
#pragma once

#include <string>

#include "base/result.h"
#include "base/unique_fd.h"

namespace overlayd {

struct ListenAddress {
    enum class Kind { Ipv4, Ipv6, Unix } kind = Kind::Ipv4;
    std::string host; // numeric address; the socket path for Unix
    unsigned port = 0;

    // Loopback addresses and unix sockets: only local processes can connect (what control = "open" requires).
    bool isLocal() const;
    std::string describe() const;
};

// Refuses anything else with a reason that says what is expected.
Result<ListenAddress> parseListenAddress(const std::string &text);

// What binding the address would refuse whatever the moment: a unix socket's folder that does not exist (the
// config loader asks, so check-config refuses it as run would).
Status checkListenFolder(const ListenAddress &address);

// A bound, listening, non-blocking socket (a stale unix socket file is replaced; its folder must exist).
Result<UniqueFd> openListeningSocket(const ListenAddress &address, int backlog);

} // namespace overlayd
