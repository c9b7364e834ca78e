// SPDX-License-Identifier: Apache-2.0
// lockExclusive and flockHolder: flock, and /proc/locks to say who holds one.
#include "drivers/files/file_lock.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include <sys/file.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>

namespace overlayd {

namespace {

// /proc/PID/comm, for a message a person can act on; empty when the process is gone or not ours to see.
std::string processName(pid_t pid)
{
    std::ifstream comm("/proc/" + std::to_string(pid) + "/comm");
    std::string name;
    std::getline(comm, name);
    return name;
}

// "MAJ:MIN:INODE" as /proc/locks writes it (major and minor in hex).
std::string lockKey(const struct stat &file)
{
    char key[64];
    std::snprintf(key, sizeof(key), "%02x:%02x:%llu", major(file.st_dev), minor(file.st_dev),
                  static_cast<unsigned long long>(file.st_ino));
    return key;
}

} // namespace

std::optional<pid_t> flockHolder(int fd)
{
    struct stat file {};
    if (::fstat(fd, &file) != 0)
        return std::nullopt;
    const std::string key = lockKey(file);
    // "1: FLOCK  ADVISORY  WRITE 1234 fd:01:5678 0 EOF"; a waiter's line has "->" after the number.
    std::ifstream locks("/proc/locks");
    for (std::string line; std::getline(locks, line);) {
        std::istringstream fields(line);
        std::string number, kind, mode, access, where;
        pid_t pid = 0;
        if (fields >> number >> kind >> mode >> access >> pid >> where && kind == "FLOCK" && where == key)
            return pid;
    }
    return std::nullopt;
}

Status lockExclusive(int fd, const std::string &path)
{
    if (::flock(fd, LOCK_EX | LOCK_NB) == 0)
        return Ok{};
    if (errno != EWOULDBLOCK)
        return makeError(ErrorCode::Io, path + ": cannot lock: " + std::strerror(errno));
    std::string holder = "another process";
    if (const std::optional<pid_t> pid = flockHolder(fd)) {
        holder = "process " + std::to_string(*pid);
        if (const std::string name = processName(*pid); !name.empty())
            holder += " (" + name + ")";
    }
    return makeError(ErrorCode::Io, path + ": locked by " + holder + ", which writes it already");
}

} // namespace overlayd
