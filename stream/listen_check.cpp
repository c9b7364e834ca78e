// SPDX-License-Identifier: Apache-2.0
// checkListenable: the bind, then who holds a port that is taken.
#include "stream/listen_check.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>

#include "base/unique_fd.h"

namespace overlayd {
namespace {

namespace fs = std::filesystem;

// The inodes of the sockets that listen on `port` (state 0A in /proc/net/tcp and tcp6), whatever their address.
std::set<std::string> listeningInodes(unsigned port)
{
    std::set<std::string> inodes;
    for (const char *table : {"/proc/net/tcp", "/proc/net/tcp6"}) {
        std::ifstream in(table);
        std::string line;
        std::getline(in, line); // the header
        while (std::getline(in, line)) {
            std::istringstream fields(line);
            std::string slot, local, remote, state, queues, timer, retransmits, uid, timeout, inode;
            fields >> slot >> local >> remote >> state >> queues >> timer >> retransmits >> uid >> timeout >> inode;
            const size_t colon = local.rfind(':');
            if (state == "0A" && colon != std::string::npos &&
                std::strtoul(local.c_str() + colon + 1, nullptr, 16) == port)
                inodes.insert(inode);
        }
    }
    return inodes;
}

// Whether one of the process's descriptors is one of the sockets.
bool holds(const fs::path &process, const std::set<std::string> &inodes)
{
    std::error_code error;
    for (fs::directory_iterator fd(process / "fd", error), end; !error && fd != end; fd.increment(error)) {
        const std::string target = fs::read_symlink(fd->path(), error).string();
        if (!error && target.starts_with("socket:[") && inodes.contains(target.substr(8, target.size() - 9)))
            return true;
        error.clear();
    }
    return false;
}

std::string firstLine(const fs::path &file)
{
    std::ifstream in(file);
    std::string line;
    std::getline(in, line);
    return line;
}

// The process holding one of the sockets (its /proc folder), this one first; none when no process this user may
// look into holds it.
std::optional<fs::path> holder(const std::set<std::string> &inodes)
{
    if (holds("/proc/self", inodes))
        return fs::path("/proc/self");
    std::error_code error;
    for (fs::directory_iterator entry("/proc", error), end; !error && entry != end; entry.increment(error)) {
        const std::string name = entry->path().filename().string();
        if (name.find_first_not_of("0123456789") == std::string::npos && holds(entry->path(), inodes))
            return entry->path();
    }
    return std::nullopt;
}

} // namespace

Status checkListenable(const std::string &host, unsigned port)
{
    sockaddr_storage address{};
    socklen_t length = 0;
    auto *v4 = reinterpret_cast<sockaddr_in *>(&address);
    auto *v6 = reinterpret_cast<sockaddr_in6 *>(&address);
    if (inet_pton(AF_INET, host.c_str(), &v4->sin_addr) == 1) {
        v4->sin_family = AF_INET;
        v4->sin_port = htons(uint16_t(port));
        length = sizeof(*v4);
    } else if (inet_pton(AF_INET6, host.c_str(), &v6->sin6_addr) == 1) {
        v6->sin6_family = AF_INET6;
        v6->sin6_port = htons(uint16_t(port));
        length = sizeof(*v6);
    } else {
        return Ok{}; // not numeric: the listen key's own check says so
    }
    const std::string where = (address.ss_family == AF_INET6 ? "[" + host + "]" : host) + ":" + std::to_string(port);
    UniqueFd socket(::socket(address.ss_family, SOCK_STREAM | SOCK_CLOEXEC, 0));
    if (!socket.isValid())
        return Ok{}; // no socket to try with: the server's own bind says what is wrong
    const int reuse = 1;
    (void)setsockopt(socket.get(), SOL_SOCKET, SO_REUSEADDR, &reuse, sizeof(reuse));
    if (bind(socket.get(), reinterpret_cast<const sockaddr *>(&address), length) == 0)
        return Ok{};
    const int failure = errno;
    if (failure != EADDRINUSE)
        return makeError(ErrorCode::InvalidArgument, "cannot listen on " + where + ": " + std::strerror(failure));
    const auto process = holder(listeningInodes(port));
    if (!process)
        return makeError(ErrorCode::InvalidArgument, where + " is in use (by a process this user cannot look into)");
    std::error_code error;
    const std::string program = fs::read_symlink(*process / "exe", error).filename().string();
    if (process->filename() == "self" || program == "overlayd")
        return Ok{}; // this daemon's own server, or the running daemon's: a reload takes it over
    return makeError(ErrorCode::InvalidArgument, where + " is in use by " + firstLine(*process / "comm") + " (pid " +
                                                     process->filename().string() + ")");
}

} // namespace overlayd
