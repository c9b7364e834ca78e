// SPDX-License-Identifier: Apache-2.0
// UniqueFd: the one owner of a file descriptor in the project (the event loop's kernel objects, V4L2 devices and
// their exported buffers).
#pragma once

#include <utility>

namespace overlayd {

// Who closes a descriptor. The kernel by default; a test seam (the V4L2 Syscalls) stands in so that a fake sees
// every close of a descriptor it handed out.
class FdCloser
{
public:
    virtual ~FdCloser() = default;
    virtual int close(int fd) = 0;
};

// ::close. Stateless, so one instance serves every descriptor.
FdCloser &kernelCloser();

// Move-only; closes through the closer that was given with the descriptor.
class UniqueFd
{
public:
    UniqueFd() = default;
    explicit UniqueFd(int fd) : closer_(&kernelCloser()), fd_(fd) {}
    UniqueFd(FdCloser &closer, int fd) : closer_(&closer), fd_(fd) {}
    UniqueFd(UniqueFd &&other) noexcept { *this = std::move(other); }
    UniqueFd &operator=(UniqueFd &&other) noexcept;
    UniqueFd(const UniqueFd &) = delete;
    UniqueFd &operator=(const UniqueFd &) = delete;
    ~UniqueFd() { reset(); }

    int get() const { return fd_; }
    bool isValid() const { return fd_ >= 0; }
    // Gives up ownership; the caller must close the fd.
    [[nodiscard]] int release() { return std::exchange(fd_, -1); }
    void reset();

private:
    FdCloser *closer_ = nullptr;
    int fd_ = -1;
};

} // namespace overlayd
