// SPDX-License-Identifier: Apache-2.0
// SegmentStore: the directory a recording writes, as the recorder needs it; the seam its tests replace.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "base/result.h"

namespace overlayd {

class SegmentStore
{
public:
    struct Entry {
        std::string name; // a file name inside the directory
        uint64_t bytes = 0;
    };

    virtual ~SegmentStore() = default;

    // The regular files of the directory (not its subdirectories, not what links point to).
    virtual Result<std::vector<Entry>> list() = 0;
    virtual Status remove(const std::string &name) = 0;
    // Within the directory, atomically: a reader sees the old name or the new one, never half a file.
    virtual Status rename(const std::string &from, const std::string &to) = 0;
    virtual Result<uint64_t> freeBytes() = 0;
    // The directory exists, is one, and takes a new file (a file is made and removed): what `run` needs.
    virtual Status checkWritable() = 0;
};

} // namespace overlayd
