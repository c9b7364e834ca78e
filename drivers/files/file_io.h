// SPDX-License-Identifier: Apache-2.0
// Owned stdio files and the whole-or-nothing reads and writes the replay sources and file sinks need.
#pragma once

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "base/result.h"

namespace overlayd {

struct FileCloser {
    void operator()(std::FILE *file) const { std::fclose(file); }
};
using UniqueFile = std::unique_ptr<std::FILE, FileCloser>;

// NotFound when the file does not exist, InvalidArgument when it is not a regular file (a directory, a device, a
// FIFO: a replay reads files), Io for any other failure (errno's text in the message).
Result<UniqueFile> openForReading(const std::string &path);
// Creates the folders a path to be written needs (failures are left to the open that follows).
void makeParentFolders(const std::string &path);
// Creates missing parent folders; append keeps what the file holds.
Result<UniqueFile> openForWriting(const std::string &path, bool append);

// How many of `size` bytes were read before end of file (a short count is a truncated file, not an error);
// Io when the read itself fails.
Result<size_t> readUpTo(std::FILE *file, void *data, size_t size, const std::string &path);
// A whole file (fewer bytes if it shrinks while being read); Malformed, naming both sizes, when it holds more than
// maxBytes, before anything is allocated.
Result<std::vector<uint8_t>> readWholeFile(const std::string &path, uintmax_t maxBytes);

Status writeAll(std::FILE *file, const void *data, size_t size, const std::string &path);

} // namespace overlayd
