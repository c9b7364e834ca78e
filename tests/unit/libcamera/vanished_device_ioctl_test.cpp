// SPDX-License-Identifier: Apache-2.0
// The ioctl shim: libcamera's calls reach it; from the rewritten object (libcamera.so, here this test) a
// VIDIOC_STREAMOFF or VIDIOC_QBUF answered with ENODEV (an unplugged device) is reported done and counted; every
// other call, answer and caller passes unchanged.
#include <cerrno>

#include <dlfcn.h>
#include <fcntl.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <linux/videodev2.h>

#include <gtest/gtest.h>

#include "drivers/libcamera/vanished_device_ioctl.h"

namespace overlayd {
namespace {

struct Call {
    int fd = -1;
    unsigned long request = 0;
    void *arg = nullptr;
};
Call lastCall;
int answerErrno = 0;

int fakeDevice(int fd, unsigned long request, void *arg)
{
    lastCall = {fd, request, arg};
    if (answerErrno == 0)
        return 0;
    errno = answerErrno;
    return -1;
}

class VanishedDeviceIoctl : public ::testing::Test
{
protected:
    void SetUp() override
    {
        setNextIoctl(&fakeDevice);
        setRewrittenCaller(reinterpret_cast<const void *>(&fakeDevice)); // this executable stands for libcamera.so
    }
    void TearDown() override
    {
        setNextIoctl(nullptr);
        setRewrittenCaller(nullptr);
    }
};

TEST_F(VanishedDeviceIoctl, IsWhatTheDynamicLinkerBindsIoctlTo)
{
    // libcamera.so's calls to ioctl are bound by the same global lookup as dlsym(RTLD_DEFAULT, "ioctl").
    EXPECT_TRUE(vanishedDeviceIoctlInstalled());
    setRewrittenCaller(nullptr);
    EXPECT_NE(rewrittenCallerFile().find("libcamera.so"), std::string::npos) << rewrittenCallerFile();
}

TEST_F(VanishedDeviceIoctl, StreamOffOnAVanishedDeviceIsReportedDone)
{
    answerErrno = ENODEV;
    int type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    const uint64_t before = vanishedDeviceCalls();
    errno = 0;
    EXPECT_EQ(::ioctl(7, VIDIOC_STREAMOFF, &type), 0);
    EXPECT_EQ(errno, 0);
    EXPECT_EQ(vanishedDeviceCalls(), before + 1);
    EXPECT_EQ(lastCall.fd, 7);
    EXPECT_EQ(lastCall.request, VIDIOC_STREAMOFF);
    EXPECT_EQ(lastCall.arg, &type);
}

TEST_F(VanishedDeviceIoctl, QueueingOnAVanishedDeviceIsReportedDone)
{
    answerErrno = ENODEV;
    v4l2_buffer buffer{};
    const uint64_t before = vanishedDeviceCalls();
    EXPECT_EQ(::ioctl(4, VIDIOC_QBUF, &buffer), 0);
    EXPECT_EQ(vanishedDeviceCalls(), before + 1);
    EXPECT_EQ(lastCall.arg, &buffer);
}

TEST_F(VanishedDeviceIoctl, OtherCallsAndFailuresPassUnchanged)
{
    const uint64_t before = vanishedDeviceCalls();
    int type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    answerErrno = ENODEV;
    v4l2_buffer buffer{};
    EXPECT_EQ(::ioctl(3, VIDIOC_DQBUF, &buffer), -1);
    EXPECT_EQ(errno, ENODEV);
    EXPECT_EQ(::ioctl(3, VIDIOC_STREAMON, &type), -1);
    EXPECT_EQ(errno, ENODEV);
    answerErrno = EBUSY;
    EXPECT_EQ(::ioctl(3, VIDIOC_STREAMOFF, &type), -1);
    EXPECT_EQ(errno, EBUSY);
    answerErrno = 0;
    EXPECT_EQ(::ioctl(3, VIDIOC_STREAMOFF, &type), 0);
    EXPECT_EQ(vanishedDeviceCalls(), before);
}

TEST_F(VanishedDeviceIoctl, OtherCallersKeepTheirErrors)
{
    // overlayd's own V4L2 code learns of an unplug from QBUF's ENODEV: only libcamera's calls are rewritten.
    setRewrittenCaller(nullptr);
    answerErrno = ENODEV;
    int type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    v4l2_buffer buffer{};
    const uint64_t before = vanishedDeviceCalls();
    EXPECT_EQ(::ioctl(3, VIDIOC_STREAMOFF, &type), -1);
    EXPECT_EQ(errno, ENODEV);
    EXPECT_EQ(::ioctl(3, VIDIOC_QBUF, &buffer), -1);
    EXPECT_EQ(errno, ENODEV);
    EXPECT_EQ(vanishedDeviceCalls(), before);
}

TEST(VanishedDeviceIoctlLibc, RealCallsReachTheCLibrary)
{
    int fds[2];
    ASSERT_EQ(::pipe(fds), 0);
    ASSERT_EQ(::write(fds[1], "abc", 3), 3);
    int pending = -1;
    EXPECT_EQ(::ioctl(fds[0], FIONREAD, &pending), 0);
    EXPECT_EQ(pending, 3);
    // A pipe is no V4L2 device: the refusal is passed on as the C library gives it (ENOTTY from the kernel;
    // qemu-user, which the arm64 tier runs under, answers an ioctl it does not know with ENOSYS).
    using LibcIoctl = int (*)(int, unsigned long, ...);
    const auto libc = reinterpret_cast<LibcIoctl>(::dlsym(RTLD_NEXT, "ioctl"));
    ASSERT_NE(libc, nullptr);
    int type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    errno = 0;
    ASSERT_EQ(libc(fds[0], VIDIOC_STREAMOFF, &type), -1);
    const int refusal = errno;
    EXPECT_TRUE(refusal == ENOTTY || refusal == ENOSYS) << refusal;
    errno = 0;
    EXPECT_EQ(::ioctl(fds[0], VIDIOC_STREAMOFF, &type), -1);
    EXPECT_EQ(errno, refusal);
    ::close(fds[0]);
    ::close(fds[1]);
}

} // namespace
} // namespace overlayd