// SPDX-License-Identifier: Apache-2.0
// NotifySocket: the test's stand-in for systemd's end of NOTIFY_SOCKET (a bound AF_UNIX datagram socket).
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <sys/types.h>
#include <vector>

namespace overlayd::test {

// CLOCK_MONOTONIC in microseconds: the clock systemd expects in MONOTONIC_USEC=.
uint64_t monotonicMicroseconds();

// One datagram as systemd would see it: its text, the sender's credentials (SCM_CREDENTIALS, which is how
// NotifyAccess=main tells the main process from others) and when it arrived.
struct Datagram {
    std::string text;
    pid_t pid = 0;
    uint64_t receivedUsec = 0; // monotonicMicroseconds() at arrival
    // "KEY=value" lines, as sd_notify's protocol defines them.
    std::map<std::string, std::string> fields() const;
    bool has(const std::string &key) const { return fields().count(key) != 0; }
};

// A temporary directory removed (with its contents) on destruction.
class TempDir
{
public:
    TempDir();
    ~TempDir();
    TempDir(const TempDir &) = delete;
    TempDir &operator=(const TempDir &) = delete;
    const std::filesystem::path &path() const { return path_; }

private:
    std::filesystem::path path_;
};

class NotifySocket
{
public:
    // Binds a datagram socket at `path` (a file system socket, as systemd uses) with SO_PASSCRED set.
    explicit NotifySocket(std::filesystem::path path);
    ~NotifySocket();
    NotifySocket(const NotifySocket &) = delete;
    NotifySocket &operator=(const NotifySocket &) = delete;

    bool ok() const { return fd_ >= 0; }
    const std::filesystem::path &path() const { return path_; }
    // The next datagram, or nothing if none arrives within `timeout`.
    std::optional<Datagram> receive(std::chrono::milliseconds timeout);
    // Everything that arrives within `duration`.
    std::vector<Datagram> collect(std::chrono::milliseconds duration);

private:
    std::filesystem::path path_;
    int fd_ = -1;
};

} // namespace overlayd::test
