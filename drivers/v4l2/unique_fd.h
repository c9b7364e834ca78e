// UniqueFd: the one owner of a file descriptor opened through the Syscalls seam.
#pragma once

#include <utility>

#include "drivers/v4l2/v4l2_syscalls.h"

namespace overlayd::v4l2 {

// Move-only; closes through the seam that opened it, so a fake sees every close.
class UniqueFd
{
public:
    UniqueFd() = default;
    UniqueFd(Syscalls &syscalls, int fd) : syscalls_(&syscalls), fd_(fd) {}
    UniqueFd(UniqueFd &&other) noexcept { *this = std::move(other); }
    UniqueFd &operator=(UniqueFd &&other) noexcept;
    UniqueFd(const UniqueFd &) = delete;
    UniqueFd &operator=(const UniqueFd &) = delete;
    ~UniqueFd() { reset(); }

    int get() const { return fd_; }
    bool isValid() const { return fd_ >= 0; }
    // Gives up ownership; the caller must close the fd.
    [[nodiscard]] int release();
    void reset();

private:
    Syscalls *syscalls_ = nullptr;
    int fd_ = -1;
};

} // namespace overlayd::v4l2
