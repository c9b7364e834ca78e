// SPDX-License-Identifier: Apache-2.0
// RequestSlots: the bookkeeping behind the header and body deadlines and the caps on incomplete requests.
#include "http/request_slots.h"

#include <algorithm>

namespace overlayd {

namespace {

// An address over its cap loses only requests at least this old: a burst of connections accepted in one pass has
// not been read yet, and its newest would otherwise shed its older neighbours before they could say anything.
constexpr auto kMinShedAge = std::chrono::seconds(1);

} // namespace

unsigned RequestSlots::count(const std::string *address) const
{
    return unsigned(std::count_if(slots_.begin(), slots_.end(), [&](const Slot &slot) {
        return incomplete(slot) && (!address || slot.address == *address);
    }));
}

RequestSlots::Slot *RequestSlots::slowest(const std::string *address, Clock::time_point before)
{
    Slot *oldest = nullptr;
    for (Slot &slot : slots_)
        if (incomplete(slot) && (!address || slot.address == *address) && slot.since <= before &&
            (!oldest || slot.since < oldest->since))
            oldest = &slot;
    return oldest;
}

std::vector<std::pair<RequestSlots::Id, ShedReason>> RequestSlots::opened(Id id, const std::string &address,
                                                                          Clock::time_point now)
{
    std::vector<std::pair<Id, ShedReason>> out;
    const auto shedSlowest = [&](const std::string *from, ShedReason reason) {
        Slot *victim = slowest(from, from ? now - kMinShedAge : Clock::time_point::max());
        if (!victim)
            return false;
        victim->shed = true;
        ++counts_[unsigned(reason)];
        out.emplace_back(victim->id, reason);
        return true;
    };
    while (count(&address) >= limits_.perAddress && shedSlowest(&address, ShedReason::PerAddress)) {
    }
    const auto live = [this] {
        return std::count_if(slots_.begin(), slots_.end(), [](const Slot &s) { return !s.shed; });
    };
    while (unsigned(live()) >= limits_.total && shedSlowest(nullptr, ShedReason::Total)) {
    }
    // Every slot serves a stream or an answer: the newcomer is the one that cannot be served.
    const bool full = unsigned(live()) >= limits_.total;
    slots_.push_back({id, address, Phase::Headers, now, full});
    if (full) {
        ++counts_[unsigned(ShedReason::Total)];
        out.emplace_back(id, ShedReason::Total);
    }
    return out;
}

void RequestSlots::phase(Id id, Phase phase, Clock::time_point now)
{
    for (Slot &slot : slots_)
        if (slot.id == id) {
            slot.phase = phase;
            slot.since = now;
        }
}

void RequestSlots::closed(Id id)
{
    std::erase_if(slots_, [id](const Slot &slot) { return slot.id == id; });
}

std::vector<std::pair<RequestSlots::Id, ShedReason>> RequestSlots::late(Clock::time_point now)
{
    std::vector<std::pair<Id, ShedReason>> out;
    for (Slot &slot : slots_) {
        if (!incomplete(slot))
            continue;
        const bool headers = slot.phase == Phase::Headers;
        if (now - slot.since < (headers ? limits_.headerDeadline : limits_.bodyDeadline))
            continue;
        const ShedReason reason = headers ? ShedReason::HeaderDeadline : ShedReason::BodyDeadline;
        slot.shed = true;
        ++counts_[unsigned(reason)];
        out.emplace_back(slot.id, reason);
    }
    return out;
}

} // namespace overlayd
