// SPDX-License-Identifier: Apache-2.0
// Segment bookkeeping over a SegmentStore. The store is listed again at each finish: other programs may delete or
// move recordings, and the figures should say what is there, not what was written.
#include "stream/record_directory.h"

#include <algorithm>

namespace overlayd {

RecordDirectory::RecordDirectory(SegmentStore &store, RecordContainer container, RetentionLimits limits)
    : store_(store), container_(container), limits_(limits)
{}

Result<std::vector<StoredSegment>> RecordDirectory::scan()
{
    auto entries = store_.list();
    if (!entries)
        return entries.error();
    std::vector<StoredSegment> segments;
    for (const SegmentStore::Entry &entry : *entries)
        if (auto file = parseSegmentFileName(entry.name, containerExtension(container_)))
            segments.push_back({std::move(*file), entry.bytes});
    return segments;
}

Status RecordDirectory::recover(WallClock::time_point now)
{
    auto segments = scan();
    if (!segments)
        return segments.error();
    for (const StoredSegment &segment : *segments) {
        if (!segment.file.partial)
            continue;
        const std::string partial = partialFileName(segment.file.finalName);
        auto done = segment.bytes == 0 ? store_.remove(partial) : store_.rename(partial, segment.file.finalName);
        if (!done)
            return done;
        figures_.recovered += segment.bytes > 0 ? 1 : 0;
    }
    return prune(now, 0);
}

std::string RecordDirectory::nextPartialName(WallClock::time_point start)
{
    const auto segments = scan();
    const std::string_view extension = containerExtension(container_);
    for (unsigned repeat = 0;; ++repeat) {
        const std::string name = segmentFileName(start, extension, repeat);
        const bool taken = segments && std::any_of(segments->begin(), segments->end(),
                                                   [&](const StoredSegment &s) { return s.file.finalName == name; });
        if (!taken)
            return partialFileName(name);
    }
}

Status RecordDirectory::finish(const std::string &partialName, WallClock::time_point now)
{
    auto file = parseSegmentFileName(partialName, containerExtension(container_));
    if (!file || !file->partial)
        return makeError(ErrorCode::InvalidArgument, "'" + partialName + "' is not a partial segment name");
    auto entries = store_.list();
    if (!entries)
        return entries.error();
    const auto entry = std::find_if(entries->begin(), entries->end(),
                                    [&](const SegmentStore::Entry &e) { return e.name == partialName; });
    if (entry == entries->end())
        return makeError(ErrorCode::NotFound, "the segment '" + partialName + "' is gone");
    if (entry->bytes == 0) {
        if (auto removed = store_.remove(partialName); !removed)
            return removed;
    } else {
        if (auto renamed = store_.rename(partialName, file->finalName); !renamed)
            return renamed;
        largest_ = std::max(largest_, entry->bytes);
    }
    return prune(now, 0);
}

Status RecordDirectory::prune(WallClock::time_point now, uint64_t currentBytes)
{
    auto segments = scan();
    if (!segments)
        return segments.error();
    std::erase_if(*segments, [](const StoredSegment &s) { return s.file.partial; });
    const std::vector<StoredSegment> doomed = segmentsToDelete(*segments, currentBytes, limits_, now);
    Status status = Ok{};
    for (const StoredSegment &segment : doomed) {
        if (auto removed = store_.remove(segment.file.finalName); !removed) {
            status = removed; // the others are still deleted: one stuck file must not stop retention
            continue;
        }
        ++figures_.deleted;
        std::erase_if(*segments, [&](const StoredSegment &s) { return s.file.finalName == segment.file.finalName; });
    }
    tally(*segments);
    return status;
}

void RecordDirectory::tally(const std::vector<StoredSegment> &finished)
{
    figures_.segments = unsigned(finished.size());
    figures_.bytes = 0;
    figures_.oldest.clear();
    const StoredSegment *oldest = nullptr;
    for (const StoredSegment &segment : finished) {
        figures_.bytes += segment.bytes;
        if (!oldest || segment.file.before(oldest->file))
            oldest = &segment;
    }
    if (oldest)
        figures_.oldest = oldest->file.finalName;
}

} // namespace overlayd
