// SPDX-License-Identifier: Apache-2.0
// Capture error paths: EAGAIN, EINTR, ENODEV/EIO, POLLERR, a failed give-back, a device missing at start.
#include <gtest/gtest.h>

#include "test_devices.h"

namespace overlayd::test {
namespace {

using std::chrono::microseconds;

struct Errors : ::testing::Test {
    CaptureRig rig;
    FakeDevice *device = nullptr;

    void SetUp() override
    {
        device = &addYuyvCamera(rig.kernel);
        rig.make(captureOptions("YUYV", 640, 480, 30.0));
        ASSERT_TRUE(rig.source->start().ok());
    }
};

TEST_F(Errors, NothingReadyIsTryAgain)
{
    auto lease = rig.source->nextFrame();
    ASSERT_FALSE(lease.ok());
    EXPECT_EQ(lease.error().code, ErrorCode::TryAgain);
}

TEST_F(Errors, EintrIsRetried)
{
    ASSERT_TRUE(device->produce(3, microseconds(0)));
    device->dqbufErrors = {-EINTR, -EINTR};
    auto lease = rig.source->nextFrame();
    ASSERT_TRUE(lease.ok()) << lease.error().message;
    EXPECT_EQ(device->dqbufCalls, 3u);
}

TEST_F(Errors, EnodevAtDqbufIsDeviceLost)
{
    device->dqbufErrors = {-ENODEV};
    auto lease = rig.source->nextFrame();
    ASSERT_FALSE(lease.ok());
    EXPECT_EQ(lease.error().code, ErrorCode::DeviceLost);
    EXPECT_NE(lease.error().message.find("VIDIOC_DQBUF"), std::string::npos);
}

TEST_F(Errors, EioAtDqbufIsDeviceLost)
{
    device->dqbufErrors = {-EIO};
    auto lease = rig.source->nextFrame();
    ASSERT_FALSE(lease.ok());
    EXPECT_EQ(lease.error().code, ErrorCode::DeviceLost);
}

TEST_F(Errors, OtherErrnoIsIo)
{
    device->dqbufErrors = {-EINVAL};
    auto lease = rig.source->nextFrame();
    ASSERT_FALSE(lease.ok());
    EXPECT_EQ(lease.error().code, ErrorCode::Io);
}

TEST_F(Errors, PollErrorWhileBuffersAreQueuedIsDeviceLost)
{
    device->pollEvents = POLLERR;
    auto lease = rig.source->nextFrame();
    ASSERT_FALSE(lease.ok());
    EXPECT_EQ(lease.error().code, ErrorCode::DeviceLost);
}

TEST_F(Errors, PollErrorWithEveryBufferLentIsOnlyTryAgain)
{
    // vb2 also answers POLLERR when no buffer is queued; that is the pipeline holding them, not a lost device.
    std::vector<FrameLease> leases;
    for (uint32_t sequence = 0; sequence < 4; ++sequence) {
        ASSERT_TRUE(device->produce(sequence, microseconds(0)));
        auto lease = rig.source->nextFrame();
        ASSERT_TRUE(lease.ok());
        leases.push_back(std::move(lease.value()));
    }
    device->pollEvents = POLLERR;
    auto lease = rig.source->nextFrame();
    ASSERT_FALSE(lease.ok());
    EXPECT_EQ(lease.error().code, ErrorCode::TryAgain);
}

TEST_F(Errors, FailedGiveBackIsReportedByTheNextFrame)
{
    ASSERT_TRUE(device->produce(0, microseconds(0)));
    auto lease = rig.source->nextFrame();
    ASSERT_TRUE(lease.ok());
    device->qbufError = -ENODEV;
    lease->reset();
    auto next = rig.source->nextFrame();
    ASSERT_FALSE(next.ok());
    EXPECT_EQ(next.error().code, ErrorCode::DeviceLost);
}

TEST_F(Errors, DeviceLostThenStopThenStartRecovers)
{
    device->dqbufErrors = {-ENODEV};
    ASSERT_EQ(rig.source->nextFrame().error().code, ErrorCode::DeviceLost);
    rig.source->stop();
    rig.kernel.unplug("/dev/video0");
    auto missing = rig.source->start();
    ASSERT_FALSE(missing.ok());
    EXPECT_EQ(missing.error().code, ErrorCode::NotFound);
    EXPECT_EQ(rig.kernel.openFds(), 0u);
}

TEST(V4l2CaptureStart, MissingDeviceIsNotFound)
{
    CaptureRig rig;
    rig.make(captureOptions("YUYV", 640, 480, 30.0, "/dev/video9"));
    auto format = rig.source->start();
    ASSERT_FALSE(format.ok());
    EXPECT_EQ(format.error().code, ErrorCode::NotFound);
    EXPECT_EQ(rig.source->eventFd(), -1);
    auto lease = rig.source->nextFrame();
    ASSERT_FALSE(lease.ok());
    EXPECT_EQ(lease.error().code, ErrorCode::DeviceLost);
}

} // namespace
} // namespace overlayd::test
