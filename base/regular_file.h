// SPDX-License-Identifier: Apache-2.0
// readRegularFile: the one way a file the daemon reads whole (a config, a calibration, an image) is opened. Only a
// regular file is read: a directory, a device or a FIFO named where a file is meant is refused with what it is,
// without blocking (a FIFO with no writer would block an ordinary open), and a file over the caller's limit is
// refused before a byte of it is read.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "base/result.h"
#include "base/unique_fd.h"

namespace overlayd {

// The error's message says what is wrong without the path ("does not exist", "is a directory, not a regular
// file", "has 2097152 bytes; at most 1048576 are read", "cannot be read: Permission denied"): the caller names the
// file the way its own messages do. Codes: NotFound only when nothing is at the path, InvalidArgument for the wrong
// kind of file or one too large, Io for a failed open or read. A file that grows while it is read past maxBytes is
// refused too.
Result<std::string> readRegularFile(const std::string &path, size_t maxBytes);
Result<std::vector<uint8_t>> readRegularFileBytes(const std::string &path, size_t maxBytes);

// The same checks, for a file read as a stream (a replay): its descriptor, open for reading (non-blocking, which a
// regular file ignores), and its size when it was opened.
struct RegularFile {
    UniqueFd fd;
    uint64_t size = 0;
};
Result<RegularFile> openRegularFile(const std::string &path, size_t maxBytes = SIZE_MAX);

// "a directory", "a character device", "a FIFO", ... for a stat() mode.
const char *fileKindName(unsigned mode);

} // namespace overlayd
