// SPDX-License-Identifier: Apache-2.0
// replaceFileContents: a file (the live drop-in, a snapshot) written whole or not at all, and never through a name
// someone else planted: the temporary is created exclusively, without following a link, in the target's folder.
#pragma once

#include <string>
#include <string_view>

#include "base/result.h"

namespace overlayd {

// Whether a replacement must survive a power cut (the live drop-in: fsync of the file and its folder) or only be
// seen whole by readers (a snapshot rewritten every few frames, where two fsyncs each time would cost the disk).
enum class Durability { Synced, Unsynced };

// Writes `text` to a new file of a random name in path's folder (O_CREAT|O_EXCL|O_NOFOLLOW, so an existing file or
// symlink of that name is never opened), fsyncs it, renames it over `path` (a symlink at `path` is replaced, not
// followed) and fsyncs the folder (Durability::Synced), so that a crash leaves the old file or the new one. An Io error
// naming the step and the file; the temporary is removed after a failure.
Status replaceFileContents(const std::string &path, std::string_view text, Durability durability = Durability::Synced);

} // namespace overlayd
