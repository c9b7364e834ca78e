// SPDX-License-Identifier: Apache-2.0
#include "stream/pending_clients.h"

#include <algorithm>

namespace overlayd {

std::vector<PendingClients::Handle> PendingClients::admit(Handle client, const std::string &address,
                                                          Clock::time_point now)
{
    std::vector<Handle> shed;
    const auto fromAddress = [&] {
        return size_t(
            std::count_if(pending_.begin(), pending_.end(), [&](const Pending &p) { return p.address == address; }));
    };
    // Oldest first: the one that has taken longest is the slowest, and a new request always finds room.
    while (!pending_.empty() && limits_.perAddress > 0 && fromAddress() >= limits_.perAddress) {
        const auto oldest =
            std::find_if(pending_.begin(), pending_.end(), [&](const Pending &p) { return p.address == address; });
        shed.push_back(oldest->client);
        pending_.erase(oldest);
    }
    while (!pending_.empty() && limits_.total > 0 && pending_.size() >= limits_.total) {
        shed.push_back(pending_.front().client);
        pending_.erase(pending_.begin());
    }
    shed_ += shed.size();
    pending_.push_back({client, address, now});
    return shed;
}

void PendingClients::started(Handle client)
{
    closed(client);
}

void PendingClients::closed(Handle client)
{
    std::erase_if(pending_, [&](const Pending &p) { return p.client == client; });
}

std::vector<PendingClients::Handle> PendingClients::expired(Clock::time_point now)
{
    std::vector<Handle> late;
    std::erase_if(pending_, [&](const Pending &p) {
        if (now - p.since < limits_.deadline)
            return false;
        late.push_back(p.client);
        return true;
    });
    timedOut_ += late.size();
    return late;
}

} // namespace overlayd
