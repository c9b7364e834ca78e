// SPDX-License-Identifier: Apache-2.0
// PendingClients: the RTSP server's connections that have not started playing yet, held to a budget so that no
// client can lock the others out. gst-rtsp-server reads a request as its bytes come, with no deadline and no cap:
// a few hundred connections that trickle a byte now and then would each hold a socket and a GstRTSPClient for
// ever. Here a connection must reach PLAY within a deadline, at most so many may be pending at once from one
// address and in all, and when a new one would pass a cap the oldest pending one (the slowest) is shed, so that
// there is always room for a new request, as nginx and lighttpd do. Clients are opaque handles; the caller closes
// what these functions return. No GStreamer here, so that the rules are tested alone.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace overlayd {

// Connections pending in all (at least a sink's highest max_clients, kMaxRtspClients), from one address (the RTSP
// sink sets its max_clients), and how long one may take from its connect to PLAY.
inline constexpr size_t kMaxPendingRtspClients = 64;
inline constexpr size_t kMaxPendingRtspClientsPerAddress = 16;
inline constexpr std::chrono::seconds kRtspPlayDeadline{10};

struct PendingClientLimits {
    size_t total = kMaxPendingRtspClients;
    size_t perAddress = kMaxPendingRtspClientsPerAddress;
    std::chrono::steady_clock::duration deadline = kRtspPlayDeadline;
};

class PendingClients
{
public:
    using Clock = std::chrono::steady_clock;
    using Handle = const void *;

    explicit PendingClients(PendingClientLimits limits = {}) : limits_(limits) {}

    // A new connection from `address` (the host, without the port): it is pending from `now`. Returns the
    // connections to close to stay within the caps: the oldest pending ones, of the same address first.
    std::vector<Handle> admit(Handle client, const std::string &address, Clock::time_point now);
    // It asked to play: no deadline and no cap applies to it any more.
    void started(Handle client);
    // It is gone (closed by either side): forgotten.
    void closed(Handle client);
    // The pending connections past the deadline at `now`, forgotten as they are returned.
    std::vector<Handle> expired(Clock::time_point now);

    size_t pending() const { return pending_.size(); }
    uint64_t shed() const { return shed_; }         // closed to make room under a cap
    uint64_t timedOut() const { return timedOut_; } // closed at the deadline

private:
    struct Pending {
        Handle client;
        std::string address;
        Clock::time_point since;
    };

    PendingClientLimits limits_;
    std::vector<Pending> pending_; // oldest first; a few dozen at most, so a vector searched in full
    uint64_t shed_ = 0, timedOut_ = 0;
};

} // namespace overlayd
