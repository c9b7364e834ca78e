// SPDX-License-Identifier: Apache-2.0
// TextFileWatch: a text file other programs write, watched with inotify. The folder is watched, not the file, so
// that a file replaced by rename (the safe way to write it), created late or deleted is followed too; and the folder
// is followed by its path (FolderWatch), so that a folder removed and made again is followed too.
#pragma once

#include <string>

#include "base/result.h"
#include "inputs/folder_watch.h"

namespace overlayd {

// The line a slot shows: the first line of `content`, other control characters dropped, cut to at most maxBytes
// at a UTF-8 character boundary.
std::string slotLine(std::string_view content, size_t maxBytes);

// Why a watched file could never be read as one: something that exists at the path and is not a regular file (a
// directory, a device, a FIFO); empty when it is one or nothing is there yet. open() refuses it, and the config
// loader asks too, so check-config refuses it as run does.
std::string watchedFileProblem(const std::string &path);

class TextFileWatch
{
public:
    // When the file counts as changed: after every write (a one-line status: the newest text at once, even from a
    // writer that keeps the file open), or only once a writer closes it or renames it in (a whole document such as
    // a path: never read half-written; a truncating `>` would otherwise read as empty first).
    enum class Reread { EveryWrite, WhenComplete };
    // The folder must exist now (a missing file is fine: it reads as empty until it appears; if the folder goes
    // later, it is waited for); an existing path that is not a regular file is refused (watchedFileProblem).
    static Result<TextFileWatch> open(const std::string &path, size_t maxBytes, Reread reread = Reread::EveryWrite);

    // Readable when something happened in the folder; consume() then says whether it was this file (or may have
    // been: the folder went or came back).
    int fd() const { return folder_.fd(); }
    bool consume() { return folder_.consume(name_); }
    // Whether the folder is watched; otherwise problem() says why the file is not followed and what is waited for.
    bool following() const { return folder_.following(); }
    const std::string &problem() const { return folder_.problem(); }
    // The file's line now ("" when it does not exist or cannot be read).
    std::string read() const;
    // The file's first maxBytes + 1 bytes (so that a caller can tell a longer file); "" when it does not exist.
    std::string readPrefix(size_t maxBytes) const;
    const std::string &path() const { return path_; }

private:
    TextFileWatch(FolderWatch folder, std::string path, std::string name, size_t maxBytes)
        : folder_(std::move(folder)), path_(std::move(path)), name_(std::move(name)), maxBytes_(maxBytes)
    {}

    FolderWatch folder_;
    std::string path_, name_; // name_: the file's name within its folder
    size_t maxBytes_;
};

} // namespace overlayd
