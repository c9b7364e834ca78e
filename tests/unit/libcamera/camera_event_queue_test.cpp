// SPDX-License-Identifier: Apache-2.0
// CameraEventQueue: events posted on another thread (libcamera's) reach the loop in order, each with one wake-up of
// an eventfd the loop polls, and nothing is decided on the posting thread.
#include <poll.h>
#include <sys/eventfd.h>
#include <unistd.h>

#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "base/unique_fd.h"
#include "drivers/libcamera/camera_event_queue.h"
#include "drivers/libcamera/camera_presence.h"

namespace overlayd {
namespace {

// The source's wake-up: a semaphore eventfd, as LibcameraSource::signal writes it.
struct Wake {
    UniqueFd fd{::eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK | EFD_SEMAPHORE)};
    std::function<void()> seam()
    {
        return [this] {
            const uint64_t one = 1;
            (void)!::write(fd.get(), &one, sizeof(one));
        };
    }
    bool readable(int timeoutMs) const
    {
        pollfd p{fd.get(), POLLIN, 0};
        return ::poll(&p, 1, timeoutMs) == 1;
    }
    unsigned drain() const
    {
        unsigned n = 0;
        uint64_t one;
        while (::read(fd.get(), &one, sizeof(one)) == sizeof(one))
            ++n;
        return n;
    }
};

TEST(CameraEventQueue, OtherThreadPostsTheLoopTakesInOrder)
{
    Wake wake;
    CameraEventQueue queue(wake.seam());
    EXPECT_FALSE(wake.readable(0));
    std::thread libcameraThread([&] {
        queue.post(CameraEvent::Kind::Disconnected, {});
        queue.post(CameraEvent::Kind::Removed, "platform/vimc.0 Sensor B");
        queue.post(CameraEvent::Kind::Added, "platform/vimc.0 Sensor B", "Sensor B");
    });
    libcameraThread.join();
    ASSERT_TRUE(wake.readable(1000));
    EXPECT_EQ(wake.drain(), 3u); // one wake-up per event: the loop's semaphore reads stay balanced
    const auto events = queue.take();
    ASSERT_EQ(events.size(), 3u);
    EXPECT_EQ(events[0].kind, CameraEvent::Kind::Disconnected);
    EXPECT_EQ(events[1].kind, CameraEvent::Kind::Removed);
    EXPECT_EQ(events[1].cameraId, "platform/vimc.0 Sensor B");
    EXPECT_EQ(events[2].kind, CameraEvent::Kind::Added);
    EXPECT_EQ(events[2].model, "Sensor B");
    EXPECT_TRUE(queue.take().empty());
    EXPECT_FALSE(queue.takeOverflow());
}

// The loop's state changes only when it takes the events, never on the thread that posted them.
TEST(CameraEventQueue, PresenceChangesOnlyWhenTheLoopApplies)
{
    Wake wake;
    CameraEventQueue queue(wake.seam());
    CameraPresence presence("0");
    presence.opened({"platform/vimc.0 Sensor B", "Sensor B"});
    std::thread([&] { queue.post(CameraEvent::Kind::Disconnected, {}); }).join();
    EXPECT_EQ(presence.state(), CameraPresence::State::Streaming);
    for (const CameraEvent &event : queue.take())
        presence.apply(event);
    EXPECT_TRUE(presence.lost());
}

TEST(CameraEventQueue, ManyPostersLoseNothing)
{
    Wake wake;
    CameraEventQueue queue(wake.seam());
    constexpr int kThreads = 4, kEach = 500;
    std::vector<std::thread> threads;
    for (int t = 0; t < kThreads; ++t)
        threads.emplace_back([&queue, t] {
            for (int i = 0; i < kEach; ++i)
                queue.post(CameraEvent::Kind::Added, std::to_string(t), std::to_string(i));
        });
    std::vector<int> next(kThreads, 0);
    size_t taken = 0;
    for (auto &thread : threads)
        thread.join();
    for (const CameraEvent &event : queue.take()) {
        const int t = std::stoi(event.cameraId);
        EXPECT_EQ(std::stoi(event.model), next[size_t(t)]++); // each poster's events in its order
        ++taken;
    }
    EXPECT_EQ(taken, size_t(kThreads * kEach));
    EXPECT_EQ(wake.drain(), unsigned(kThreads * kEach));
}

} // namespace
} // namespace overlayd