// SPDX-License-Identifier: Apache-2.0
// DeviceRemovalWatch: the kernel's uevents, read for the removal of a camera's device nodes.
#pragma once

#include <optional>
#include <string_view>
#include <vector>

#include <sys/types.h>

#include "base/unique_fd.h"

namespace overlayd {

// The device number a kernel uevent removes ("remove@..." with MAJOR= and MINOR=), or nullopt for any other event.
std::optional<dev_t> removedDevice(std::string_view uevent);

// libcamera 0.3.2 reports an unplug for uvcvideo cameras only; any other camera whose device goes away just stops
// delivering frames, and a manager that still lists it aborts when the device comes back. The kernel announces
// every device node's removal on the uevent netlink socket (with or without udevd), so the source reads it and
// reports the camera lost as soon as one of its nodes (libcamera's SystemDevices) goes, instead of waiting for
// the stall timeout. The socket can be polled by the daemon's loop; without it (refused), the stall timeout
// still applies.
class DeviceRemovalWatch
{
public:
    DeviceRemovalWatch();

    int fd() const { return socket_.get(); }
    // Reads every uevent waiting (never blocks); true when one of them removed a device of `devices`.
    bool takeRemoval(const std::vector<dev_t> &devices);

private:
    UniqueFd socket_;
};

} // namespace overlayd