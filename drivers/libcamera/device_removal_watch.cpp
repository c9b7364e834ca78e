// SPDX-License-Identifier: Apache-2.0
// DeviceRemovalWatch: a NETLINK_KOBJECT_UEVENT socket on the kernel's group, and the parsing of its events.
#include "drivers/libcamera/device_removal_watch.h"

#include <algorithm>
#include <array>
#include <charconv>

#include <sys/socket.h>
#include <sys/sysmacros.h>

#include <linux/netlink.h>

namespace overlayd {

namespace {

// The kernel's own uevents (udevd re-sends its processed ones on group 2).
constexpr unsigned kKernelUeventGroup = 1;

std::optional<unsigned> number(std::string_view text)
{
    unsigned value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc{} || end != text.data() + text.size())
        return std::nullopt;
    return value;
}

} // namespace

std::optional<dev_t> removedDevice(std::string_view uevent)
{
    // "ACTION@DEVPATH" then NUL-separated KEY=VALUE fields.
    if (!uevent.starts_with("remove@"))
        return std::nullopt;
    std::optional<unsigned> major, minor;
    while (!uevent.empty()) {
        const size_t end = std::min(uevent.find('\0'), uevent.size());
        const std::string_view field = uevent.substr(0, end);
        if (field.starts_with("MAJOR="))
            major = number(field.substr(6));
        else if (field.starts_with("MINOR="))
            minor = number(field.substr(6));
        uevent.remove_prefix(std::min(end + 1, uevent.size()));
    }
    if (!major || !minor)
        return std::nullopt;
    return makedev(*major, *minor);
}

DeviceRemovalWatch::DeviceRemovalWatch()
    : socket_(::socket(AF_NETLINK, SOCK_DGRAM | SOCK_CLOEXEC | SOCK_NONBLOCK, NETLINK_KOBJECT_UEVENT))
{
    sockaddr_nl address{};
    address.nl_family = AF_NETLINK;
    address.nl_groups = kKernelUeventGroup;
    if (socket_.isValid() && ::bind(socket_.get(), reinterpret_cast<sockaddr *>(&address), sizeof(address)) < 0)
        socket_.reset();
}

bool DeviceRemovalWatch::takeRemoval(const std::vector<dev_t> &devices)
{
    bool removed = false;
    std::array<char, 8192> buffer; // a uevent is at most 2048 bytes of environment plus its header
    while (socket_.isValid()) {
        sockaddr_nl sender{};
        socklen_t senderSize = sizeof(sender);
        const ssize_t n = ::recvfrom(socket_.get(), buffer.data(), buffer.size(), 0,
                                     reinterpret_cast<sockaddr *>(&sender), &senderSize);
        if (n <= 0)
            break; // EAGAIN: all read (an overflow, ENOBUFS, loses events: the stall timeout remains)
        if (sender.nl_pid != 0)
            continue; // the kernel's events only
        const auto device = removedDevice(std::string_view(buffer.data(), size_t(n)));
        if (device && std::find(devices.begin(), devices.end(), *device) != devices.end())
            removed = true;
    }
    return removed;
}

} // namespace overlayd