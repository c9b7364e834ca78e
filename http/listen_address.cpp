// SPDX-License-Identifier: Apache-2.0
// Listen addresses: parsed strictly (numeric hosts only, so that nothing waits on a resolver at start-up) and
// opened as sockets the daemon owns and hands to libmicrohttpd.
#include "http/listen_address.h"

#include <arpa/inet.h>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <filesystem>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

namespace overlayd {

namespace {

constexpr std::string_view kUnixPrefix = "unix:";

Error invalid(const std::string &text, const std::string &why)
{
    return makeError(ErrorCode::InvalidArgument,
                     "'" + text + "': " + why +
                         " (expected \"127.0.0.1:8080\", \"[::1]:8080\" or \"unix:/run/x.sock\")");
}

Result<unsigned> parsePort(const std::string &text, std::string_view digits)
{
    unsigned port = 0;
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), port);
    if (digits.empty() || error != std::errc() || end != digits.data() + digits.size() || port == 0 || port > 65535)
        return invalid(text, "the port must be a number from 1 to 65535");
    return port;
}

Status sysError(const std::string &what)
{
    return makeError(ErrorCode::Io, what + ": " + std::strerror(errno));
}

} // namespace

bool ListenAddress::isLocal() const
{
    if (kind == Kind::Unix)
        return true;
    if (kind == Kind::Ipv6)
        return host == "::1";
    in_addr address{};
    return inet_pton(AF_INET, host.c_str(), &address) == 1 && (ntohl(address.s_addr) >> 24) == 127;
}

std::string ListenAddress::describe() const
{
    switch (kind) {
    case Kind::Unix:
        return "unix:" + host;
    case Kind::Ipv6:
        return "[" + host + "]:" + std::to_string(port);
    case Kind::Ipv4:
        break;
    }
    return host + ":" + std::to_string(port);
}

Result<ListenAddress> parseListenAddress(const std::string &text)
{
    ListenAddress out;
    if (text.rfind(kUnixPrefix, 0) == 0) {
        out.kind = ListenAddress::Kind::Unix;
        out.host = text.substr(kUnixPrefix.size());
        if (out.host.empty() || out.host.front() != '/')
            return invalid(text, "a unix socket needs an absolute path");
        if (out.host.size() >= sizeof(sockaddr_un::sun_path))
            return invalid(text, "the socket path is longer than " + std::to_string(sizeof(sockaddr_un::sun_path) - 1) +
                                     " bytes");
        return out;
    }
    const size_t colon = text.rfind(':');
    if (colon == std::string::npos)
        return invalid(text, "no port");
    std::string host = text.substr(0, colon);
    auto port = parsePort(text, std::string_view(text).substr(colon + 1));
    if (!port)
        return port.error();
    out.port = *port;
    if (host.size() >= 2 && host.front() == '[' && host.back() == ']') {
        out.kind = ListenAddress::Kind::Ipv6;
        out.host = host.substr(1, host.size() - 2);
        in6_addr address{};
        if (inet_pton(AF_INET6, out.host.c_str(), &address) != 1)
            return invalid(text, "'" + out.host + "' is not an IPv6 address");
        return out;
    }
    out.host = host == "localhost" ? "127.0.0.1" : host;
    in_addr address{};
    if (inet_pton(AF_INET, out.host.c_str(), &address) != 1)
        return invalid(text, "'" + host + "' is not a numeric IPv4 address (IPv6 goes in brackets)");
    return out;
}

Status checkListenFolder(const ListenAddress &address)
{
    if (address.kind != ListenAddress::Kind::Unix)
        return Ok{};
    const std::string folder = std::filesystem::path(address.host).parent_path().string();
    std::error_code error;
    if (!std::filesystem::is_directory(folder, error))
        return makeError(ErrorCode::NotFound,
                         "the socket's folder " + folder + " does not exist or is not a folder (bind would fail)");
    return Ok{};
}

Result<UniqueFd> openListeningSocket(const ListenAddress &address, int backlog)
{
    if (Status folder = checkListenFolder(address); !folder)
        return makeError(folder.error().code, "cannot listen on " + address.describe() + ": " + folder.error().message);
    const int family = address.kind == ListenAddress::Kind::Unix   ? AF_UNIX
                       : address.kind == ListenAddress::Kind::Ipv6 ? AF_INET6
                                                                   : AF_INET;
    UniqueFd fd(::socket(family, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0));
    if (fd.get() < 0)
        return sysError("socket").error();
    int yes = 1;
    sockaddr_storage storage{};
    socklen_t length = 0;
    if (family == AF_UNIX) {
        auto *un = reinterpret_cast<sockaddr_un *>(&storage);
        un->sun_family = AF_UNIX;
        std::memcpy(un->sun_path, address.host.c_str(), address.host.size() + 1);
        length = sizeof(sockaddr_un);
        struct stat existing {};
        // A socket left by a previous run would make bind() fail; anything else at the path is not ours to delete.
        if (::lstat(address.host.c_str(), &existing) == 0 && S_ISSOCK(existing.st_mode))
            ::unlink(address.host.c_str());
    } else if (family == AF_INET6) {
        auto *in6 = reinterpret_cast<sockaddr_in6 *>(&storage);
        in6->sin6_family = AF_INET6;
        in6->sin6_port = htons(uint16_t(address.port));
        inet_pton(AF_INET6, address.host.c_str(), &in6->sin6_addr);
        length = sizeof(sockaddr_in6);
        ::setsockopt(fd.get(), IPPROTO_IPV6, IPV6_V6ONLY, &yes, sizeof(yes)); // "[::]" means IPv6; say 0.0.0.0 too
    } else {
        auto *in = reinterpret_cast<sockaddr_in *>(&storage);
        in->sin_family = AF_INET;
        in->sin_port = htons(uint16_t(address.port));
        inet_pton(AF_INET, address.host.c_str(), &in->sin_addr);
        length = sizeof(sockaddr_in);
    }
    if (family != AF_UNIX)
        ::setsockopt(fd.get(), SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
    if (::bind(fd.get(), reinterpret_cast<const sockaddr *>(&storage), length) != 0)
        return sysError("cannot listen on " + address.describe()).error();
    if (::listen(fd.get(), backlog) != 0)
        return sysError("listen on " + address.describe()).error();
    return fd;
}

} // namespace overlayd
