// SPDX-License-Identifier: Apache-2.0
// RequestSlots: which connections are in the middle of a request, since when, and which of them to close. A client
// that trickles its headers a byte at a time keeps libmicrohttpd's idle timeout from ever firing, and a few hundred
// of them would hold every slot; here each request has fixed deadlines (headers, then body) counted from its start,
// and a new connection always finds room: the slowest incomplete request of its address, or of all, is shed first
// (as nginx and lighttpd do).
#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

namespace overlayd {

struct SlotLimits {
    unsigned perAddress = 8; // incomplete requests from one client address
    unsigned total = 32;     // connections of any kind (max_clients): beyond, the slowest incomplete request goes
    std::chrono::milliseconds headerDeadline{10000};
    std::chrono::milliseconds bodyDeadline{30000};
};

// Why a connection was closed: each counted apart in /metrics.
enum class ShedReason { HeaderDeadline, BodyDeadline, PerAddress, Total };

class RequestSlots
{
public:
    using Clock = std::chrono::steady_clock;
    using Id = uint64_t;
    enum class Phase { Headers, Body, Serving };

    explicit RequestSlots(SlotLimits limits) : limits_(limits) {}

    // A new connection (waiting for its headers): the connections to close so that it fits, the slowest first (the
    // new one itself when every other serves a stream or an answer).
    std::vector<std::pair<Id, ShedReason>> opened(Id id, const std::string &address, Clock::time_point now);
    // Headers complete (Body), request complete (Serving), answered and kept alive (Headers again).
    void phase(Id id, Phase phase, Clock::time_point now);
    void closed(Id id);
    // Requests past their deadline; each is returned once.
    std::vector<std::pair<Id, ShedReason>> late(Clock::time_point now);

    uint64_t shedCount(ShedReason reason) const { return counts_[unsigned(reason)]; }

private:
    struct Slot {
        Id id;
        std::string address;
        Phase phase;
        Clock::time_point since;
        bool shed = false; // closing: neither counted nor chosen again
    };
    bool incomplete(const Slot &slot) const { return !slot.shed && slot.phase != Phase::Serving; }
    Slot *slowest(const std::string *address, Clock::time_point before);
    unsigned count(const std::string *address) const;

    SlotLimits limits_;
    std::vector<Slot> slots_; // few hundred at most (max_clients bounds them): a scan is cheaper than an index
    uint64_t counts_[4] = {};
};

} // namespace overlayd
