// SPDX-License-Identifier: Apache-2.0
#include "http/jpeg_feed.h"

#include <cerrno>
#include <cstring>
#include <sys/eventfd.h>
#include <unistd.h>

namespace overlayd {

Result<std::unique_ptr<JpegFeed>> JpegFeed::create()
{
    UniqueFd wake(::eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC));
    if (wake.get() < 0)
        return makeError(ErrorCode::Io, std::string("eventfd: ") + std::strerror(errno));
    return std::unique_ptr<JpegFeed>(new JpegFeed(std::move(wake)));
}

void JpegFeed::publish(std::vector<uint8_t> bytes, uint64_t sequence, int64_t timestampUs, bool raw)
{
    auto frame = std::make_shared<JpegFrame>();
    frame->bytes = std::move(bytes);
    frame->sequence = sequence;
    frame->timestampUs = timestampUs;
    {
        std::lock_guard lock(mutex_);
        auto &slot = raw ? latestRaw_ : latest_;
        frame->generation = slot ? slot->generation + 1 : 1;
        slot = std::move(frame);
    }
    ++published_;
    const uint64_t one = 1;
    // A full counter (never, in practice) still leaves the fd readable: the wake-up is not lost.
    [[maybe_unused]] const ssize_t written = ::write(wake_.get(), &one, sizeof(one));
}

void JpegFeed::consumeWake()
{
    uint64_t count = 0;
    [[maybe_unused]] const ssize_t got = ::read(wake_.get(), &count, sizeof(count));
}

std::shared_ptr<const JpegFrame> JpegFeed::latest(bool raw) const
{
    std::lock_guard lock(mutex_);
    return raw ? latestRaw_ : latest_;
}

} // namespace overlayd
