// SPDX-License-Identifier: Apache-2.0
// SinkFile: the file a Y4M or raw sink writes. It never blocks the daemon to open: a FIFO that nobody reads yet is
// opened on a later frame, once a reader is there (until then each frame fails as "no reader"); a regular file is
// locked against a second writer before anything in it changes. A FIFO's reader that goes away closes it, and the
// next reader gets the prologue (the Y4M header) first, as the first one did.
#pragma once

#include <cstdio>
#include <string>

#include "base/result.h"
#include "drivers/files/file_io.h"

namespace overlayd {

class SinkFile
{
public:
    explicit SinkFile(std::string path) : path_(std::move(path)) {}

    // append keeps what the file holds (a re-open for the same stream); prologue is written first thing after the
    // file is really open (a Y4M header). Io for a file another process holds, naming it.
    Status open(bool append, std::string prologue = {});
    // The open file; a FIFO still without a reader is tried once more and is Io ("no reader") when it still has none.
    Result<std::FILE *> get();
    // Writes to the open file (get()'s). A FIFO whose reader went away (EPIPE) is closed and waits for the next one.
    Status write(const void *data, size_t size);
    // Flushes and closes (and so unlocks); a FIFO that never had a reader has nothing to close. A FIFO with a reader
    // is only flushed and kept, parked: closing it would end its reader's stream (ffplay quits at end of file) when
    // the sink is only being re-opened for the same stream (a reload, a camera re-opened); open(append) resumes it,
    // any other open or the destructor closes it.
    Status close();

private:
    Status tryOpen();
    Status closeFile();
    // A FIFO whose reader is gone: closed, and the next reader gets readerPrologue_ first.
    void readerGone();

    std::string path_;
    UniqueFile file_;
    bool wanted_ = false; // between open() and close()
    bool append_ = false;
    std::string prologue_;       // written first thing once the file is open
    std::string readerPrologue_; // what each new reader of a FIFO needs first (the whole stream header)
    bool fifo_ = false;
};

} // namespace overlayd
