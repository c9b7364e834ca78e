// SPDX-License-Identifier: Apache-2.0
// The shared CameraManager (libcamera's own, no camera needed): shared while not retired; once retired it is not
// handed out again, and a fresh manager starts when its last holder let go.
#include <cstdlib>
#include <string>

#include <gtest/gtest.h>

#include "drivers/libcamera/camera_manager.h"

namespace overlayd {
namespace {

TEST(CameraManager, SharedWhileHeld)
{
    auto first = cameraManager();
    ASSERT_TRUE(first) << first.error().message;
    auto second = cameraManager();
    ASSERT_TRUE(second) << second.error().message;
    EXPECT_EQ(first->get(), second->get());
}

TEST(CameraManager, RetiredIsNotHandedOutAgainAndAFreshOneFollows)
{
    auto old = cameraManager();
    ASSERT_TRUE(old) << old.error().message;
    retireCameraManager();
    auto refused = cameraManager();
    ASSERT_FALSE(refused);
    EXPECT_EQ(refused.error().code, ErrorCode::DeviceLost);
    std::weak_ptr<libcamera::CameraManager> watch = *old;
    old = makeError(ErrorCode::Io, "let go");
    EXPECT_TRUE(watch.expired());
    auto fresh = cameraManager();
    ASSERT_TRUE(fresh) << fresh.error().message;
    auto shared = cameraManager(); // the fresh one is not retired
    ASSERT_TRUE(shared);
    EXPECT_EQ(fresh->get(), shared->get());
}

TEST(CameraManager, RetiringWhenNoneRunsRetiresNothing)
{
    retireCameraManager();
    auto manager = cameraManager();
    ASSERT_TRUE(manager) << manager.error().message;
    auto again = cameraManager();
    ASSERT_TRUE(again) << again.error().message;
}

TEST(CameraManager, OnlyTheFirstStartIsLoggedByLibcamera)
{
    // A retry starts a fresh manager every few seconds: libcamera's "libcamera v0.3.2" INFO line once, not each time.
    {
        auto first = cameraManager();
        ASSERT_TRUE(first) << first.error().message;
    }
    ::testing::internal::CaptureStderr();
    {
        auto again = cameraManager();
        ASSERT_TRUE(again) << again.error().message;
    }
    const std::string logged = ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(logged.find("libcamera v"), std::string::npos) << logged;
}

} // namespace
} // namespace overlayd