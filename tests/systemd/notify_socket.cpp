// SPDX-License-Identifier: Apache-2.0
// NotifySocket: receives sd_notify datagrams with their sender credentials, as systemd's manager does.
#include "notify_socket.h"

#include <cstdlib>
#include <cstring>
#include <ctime>
#include <poll.h>
#include <sstream>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

namespace overlayd::test {

uint64_t monotonicMicroseconds()
{
    timespec now{};
    clock_gettime(CLOCK_MONOTONIC, &now);
    return uint64_t(now.tv_sec) * 1000000u + uint64_t(now.tv_nsec) / 1000u;
}

std::map<std::string, std::string> Datagram::fields() const
{
    std::map<std::string, std::string> result;
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) {
        auto equals = line.find('=');
        if (equals != std::string::npos)
            result[line.substr(0, equals)] = line.substr(equals + 1);
    }
    return result;
}

TempDir::TempDir()
{
    std::string pattern = (std::filesystem::temp_directory_path() / "overlayd-systemd-XXXXXX").string();
    if (mkdtemp(pattern.data()) != nullptr)
        path_ = pattern;
}

TempDir::~TempDir()
{
    std::error_code ignored;
    if (!path_.empty())
        std::filesystem::remove_all(path_, ignored);
}

NotifySocket::NotifySocket(std::filesystem::path path) : path_(std::move(path))
{
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    if (path_.string().size() >= sizeof(address.sun_path))
        return;
    std::strcpy(address.sun_path, path_.c_str());
    fd_ = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    int one = 1;
    if (fd_ < 0 || setsockopt(fd_, SOL_SOCKET, SO_PASSCRED, &one, sizeof(one)) < 0 ||
        bind(fd_, reinterpret_cast<sockaddr *>(&address), sizeof(address)) < 0) {
        if (fd_ >= 0)
            close(fd_);
        fd_ = -1;
    }
}

NotifySocket::~NotifySocket()
{
    if (fd_ >= 0)
        close(fd_);
}

std::optional<Datagram> NotifySocket::receive(std::chrono::milliseconds timeout)
{
    pollfd waiter{fd_, POLLIN, 0};
    if (fd_ < 0 || poll(&waiter, 1, int(timeout.count())) <= 0)
        return std::nullopt;

    char text[4096];
    alignas(cmsghdr) char control[CMSG_SPACE(sizeof(ucred))];
    iovec part{text, sizeof(text) - 1};
    msghdr message{};
    message.msg_iov = &part;
    message.msg_iovlen = 1;
    message.msg_control = control;
    message.msg_controllen = sizeof(control);
    ssize_t length = recvmsg(fd_, &message, MSG_DONTWAIT);
    if (length < 0)
        return std::nullopt;

    Datagram datagram;
    datagram.receivedUsec = monotonicMicroseconds();
    datagram.text.assign(text, size_t(length));
    for (cmsghdr *header = CMSG_FIRSTHDR(&message); header; header = CMSG_NXTHDR(&message, header)) {
        if (header->cmsg_level == SOL_SOCKET && header->cmsg_type == SCM_CREDENTIALS) {
            ucred credentials{};
            std::memcpy(&credentials, CMSG_DATA(header), sizeof(credentials));
            datagram.pid = credentials.pid;
        }
    }
    return datagram;
}

std::vector<Datagram> NotifySocket::collect(std::chrono::milliseconds duration)
{
    std::vector<Datagram> result;
    auto end = std::chrono::steady_clock::now() + duration;
    for (auto now = std::chrono::steady_clock::now(); now < end; now = std::chrono::steady_clock::now()) {
        auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - now);
        if (auto datagram = receive(left + std::chrono::milliseconds(1)))
            result.push_back(std::move(*datagram));
    }
    return result;
}

} // namespace overlayd::test
