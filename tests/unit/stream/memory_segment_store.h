// SPDX-License-Identifier: Apache-2.0
// MemorySegmentStore: a SegmentStore in a map, with failures on demand, for the recorder's tests.
#pragma once

#include <map>
#include <set>

#include "stream/segment_store.h"

namespace overlayd {

class MemorySegmentStore : public SegmentStore
{
public:
    Result<std::vector<Entry>> list() override
    {
        std::vector<Entry> out;
        for (const auto &[name, bytes] : files)
            out.push_back({name, bytes});
        return out;
    }
    Status remove(const std::string &name) override
    {
        if (stuck.count(name) || !files.erase(name))
            return makeError(ErrorCode::Io, "cannot remove " + name);
        return Ok{};
    }
    Status rename(const std::string &from, const std::string &to) override
    {
        const auto it = files.find(from);
        if (it == files.end())
            return makeError(ErrorCode::NotFound, from);
        files[to] = it->second;
        files.erase(from);
        return Ok{};
    }
    Result<uint64_t> freeBytes() override { return free; }
    Status checkWritable() override { return Ok{}; }

    std::map<std::string, uint64_t> files;
    std::set<std::string> stuck; // remove() fails for these
    uint64_t free = 0;
};

} // namespace overlayd
