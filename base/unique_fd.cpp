// SPDX-License-Identifier: Apache-2.0
// UniqueFd: moves and closing.
#include "base/unique_fd.h"

#include <unistd.h>

namespace overlayd {

namespace {

class KernelCloser final : public FdCloser
{
public:
    int close(int fd) override { return ::close(fd); }
};

} // namespace

FdCloser &kernelCloser()
{
    static KernelCloser closer;
    return closer;
}

UniqueFd &UniqueFd::operator=(UniqueFd &&other) noexcept
{
    if (this != &other) {
        reset();
        closer_ = other.closer_;
        fd_ = other.release();
    }
    return *this;
}

void UniqueFd::reset()
{
    if (fd_ >= 0)
        closer_->close(std::exchange(fd_, -1));
}

} // namespace overlayd
