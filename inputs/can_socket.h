// SPDX-License-Identifier: Apache-2.0
// CanSocket: one signal's frames from a SocketCAN interface (can0, vcan0, ...), through the kernel's own raw CAN
// socket API: a filter in the kernel lets only the signal's id through, so a busy bus wakes the daemon only for
// the frames it wants.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "base/result.h"
#include "base/unique_fd.h"

namespace overlayd {

struct CanId {
    uint32_t id = 0;
    bool extended = false; // 29-bit
    bool operator==(const CanId &) const = default;
};

// A received data frame: its id and data bytes (the DLC says how many are valid).
struct CanFrame {
    CanId id;
    uint8_t length = 0;
    uint8_t data[8]{};
    std::span<const uint8_t> bytes() const { return {data, length}; }
};

// Why the kernel could never name an interface so (its dev_valid_name(): 1..IFNAMSIZ-1 bytes, not "." or "..",
// no '/', ':' or whitespace); empty when it could. The config loader asks too, so check-config refuses the name.
std::string canInterfaceProblem(std::string_view name);

class CanSocket
{
public:
    // Binds a non-blocking raw socket on the interface, filtered to the id (remote frames and error frames are
    // not received). NotFound when the interface does not exist, Io otherwise (errno in the message; ENETDOWN while
    // the interface is down).
    static Result<CanSocket> open(const std::string &interface, CanId id);

    int fd() const { return fd_.get(); }
    // The next queued frame: false when none is queued (EAGAIN); an error when the interface went down or away.
    Result<bool> read(CanFrame &frame);

private:
    explicit CanSocket(UniqueFd fd) : fd_(std::move(fd)) {}
    UniqueFd fd_;
};

} // namespace overlayd
