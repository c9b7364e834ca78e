// SPDX-License-Identifier: Apache-2.0
// The kernel's CAN_RAW API (Documentation/networking/can.rst): socket(PF_CAN, SOCK_RAW, CAN_RAW), a CAN_RAW_FILTER
// of one id (with CAN_EFF_FLAG and CAN_RTR_FLAG in the mask, so that the id's width must match and remote frames
// are dropped), bound to the interface's index.
#include "inputs/can_socket.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>

#include <linux/can.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <sys/socket.h>
#include <unistd.h>

namespace overlayd {

namespace {

Error socketError(const std::string &what, const std::string &interface)
{
    const int error = errno;
    return makeError(error == ENODEV ? ErrorCode::NotFound : ErrorCode::Io,
                     "CAN interface " + interface + ": " + what + ": " + std::strerror(error));
}

} // namespace

std::string canInterfaceProblem(std::string_view name)
{
    const auto forbidden = [](char c) {
        return c == '/' || c == ':' || std::isspace(static_cast<unsigned char>(c));
    };
    if (name.empty() || name.size() >= IFNAMSIZ || name == "." || name == ".." ||
        std::any_of(name.begin(), name.end(), forbidden))
        return "a network interface name of 1.." + std::to_string(IFNAMSIZ - 1) +
               " bytes without '/', ':' or blanks, as the kernel requires (e.g. can0), got \"" +
               std::string(name.substr(0, 64)) + "\"";
    return {};
}

Result<CanSocket> CanSocket::open(const std::string &interface, CanId id)
{
    if (const std::string problem = canInterfaceProblem(interface); !problem.empty())
        return makeError(ErrorCode::InvalidArgument, "CAN interface: " + problem);
    UniqueFd fd(::socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW));
    if (fd.get() < 0)
        return socketError("socket(PF_CAN)", interface);
    const unsigned index = if_nametoindex(interface.c_str());
    if (index == 0)
        return socketError("no such interface", interface);
    can_filter filter{};
    filter.can_id = id.extended ? (id.id | CAN_EFF_FLAG) : id.id;
    filter.can_mask = (id.extended ? CAN_EFF_MASK : CAN_SFF_MASK) | CAN_EFF_FLAG | CAN_RTR_FLAG;
    if (::setsockopt(fd.get(), SOL_CAN_RAW, CAN_RAW_FILTER, &filter, sizeof filter) != 0)
        return socketError("CAN_RAW_FILTER", interface);
    sockaddr_can address{};
    address.can_family = AF_CAN;
    address.can_ifindex = int(index);
    if (::bind(fd.get(), reinterpret_cast<const sockaddr *>(&address), sizeof address) != 0)
        return socketError("bind", interface);
    // An interface that is down binds, with ENETDOWN pending (net/can/raw.c raw_bind): refused here, so that the
    // retry goes on until it is up instead of opening a socket whose first read fails.
    int pending = 0;
    socklen_t size = sizeof pending;
    if (::getsockopt(fd.get(), SOL_SOCKET, SO_ERROR, &pending, &size) == 0 && pending != 0) {
        errno = pending;
        return socketError("bind", interface);
    }
    return CanSocket(std::move(fd));
}

Result<bool> CanSocket::read(CanFrame &frame)
{
    can_frame raw{};
    const ssize_t n = ::recv(fd_.get(), &raw, sizeof raw, 0);
    if (n < 0) {
        if (errno == EAGAIN || errno == EINTR)
            return false;
        return makeError(ErrorCode::Io, std::string("CAN read: ") + std::strerror(errno));
    }
    if (size_t(n) != sizeof raw)
        return makeError(ErrorCode::Malformed, "CAN read: a short frame of " + std::to_string(n) + " bytes");
    frame.id.extended = (raw.can_id & CAN_EFF_FLAG) != 0;
    frame.id.id = raw.can_id & (frame.id.extended ? CAN_EFF_MASK : CAN_SFF_MASK);
    frame.length = std::min<uint8_t>(raw.len, 8);
    std::memcpy(frame.data, raw.data, sizeof frame.data);
    return true;
}

} // namespace overlayd
