// SPDX-License-Identifier: Apache-2.0
// DirectorySegmentStore: a SegmentStore on a real directory (POSIX calls on its path).
#pragma once

#include <string>

#include "stream/segment_store.h"

namespace overlayd {

class DirectorySegmentStore : public SegmentStore
{
public:
    explicit DirectorySegmentStore(std::string directory);

    Result<std::vector<Entry>> list() override;
    Status remove(const std::string &name) override;
    Status rename(const std::string &from, const std::string &to) override;
    Result<uint64_t> freeBytes() override;
    Status checkWritable() override;

    const std::string &directory() const { return directory_; }

private:
    std::string pathOf(const std::string &name) const { return directory_ + "/" + name; }

    std::string directory_;
};

} // namespace overlayd
