// SPDX-License-Identifier: Apache-2.0
// An exclusive advisory lock on an output file, so that a second writer (another overlayd on the same path) is
// refused with the process that holds it instead of interleaving its frames with ours.
#pragma once

#include <optional>
#include <string>

#include <sys/types.h>

#include "base/result.h"

namespace overlayd {

// flock(LOCK_EX | LOCK_NB) on fd (held until the file is closed). Io, naming the holder, when another open file
// holds it: "locked by process 1234 (overlayd)".
Status lockExclusive(int fd, const std::string &path);

// The process /proc/locks names for a flock on the file behind fd (flock, unlike fcntl's F_GETLK, has no call that
// answers it); nothing when no lock is listed.
std::optional<pid_t> flockHolder(int fd);

} // namespace overlayd
