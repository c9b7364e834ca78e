// UniqueFd: moves and closing.
#include "drivers/v4l2/unique_fd.h"

#include <utility>

namespace overlayd::v4l2 {

UniqueFd &UniqueFd::operator=(UniqueFd &&other) noexcept
{
    if (this != &other) {
        reset();
        syscalls_ = other.syscalls_;
        fd_ = other.release();
    }
    return *this;
}

int UniqueFd::release()
{
    return std::exchange(fd_, -1);
}

void UniqueFd::reset()
{
    if (fd_ >= 0)
        syscalls_->close(std::exchange(fd_, -1));
}

} // namespace overlayd::v4l2
