// SPDX-License-Identifier: Apache-2.0
// DeviceRemovalWatch: a kernel uevent that removes a device node gives that node's number; any other event none.
#include <string>

#include <sys/sysmacros.h>

#include <gtest/gtest.h>

#include "drivers/libcamera/device_removal_watch.h"

namespace overlayd {
namespace {

using namespace std::string_literals;

// As the kernel sends it (vimc's capture node unbound in the QEMU guest, fields as in `udevadm monitor -k -p`).
const std::string kVideoRemoved = "remove@/devices/platform/vimc.0/video4linux/video2\0"
                                  "ACTION=remove\0"
                                  "DEVPATH=/devices/platform/vimc.0/video4linux/video2\0"
                                  "SUBSYSTEM=video4linux\0"
                                  "MAJOR=81\0"
                                  "MINOR=2\0"
                                  "DEVNAME=video2\0"
                                  "SEQNUM=2345\0"s;

TEST(DeviceRemovalWatch, ARemovedNodeGivesItsNumber)
{
    EXPECT_EQ(removedDevice(kVideoRemoved), makedev(81, 2));
    const std::string media = "remove@/devices/platform/vimc.0/media0\0ACTION=remove\0SUBSYSTEM=media\0"
                              "MAJOR=238\0MINOR=0\0DEVNAME=media0\0"s;
    EXPECT_EQ(removedDevice(media), makedev(238, 0));
}

TEST(DeviceRemovalWatch, OtherEventsGiveNone)
{
    std::string added = kVideoRemoved;
    added.replace(0, 6, "add");
    EXPECT_EQ(removedDevice(added), std::nullopt);
    EXPECT_EQ(removedDevice("remove@/devices/platform/vimc.0\0ACTION=remove\0SUBSYSTEM=platform\0"s), std::nullopt);
    EXPECT_EQ(removedDevice("remove@/x\0MAJOR=81\0MINOR=two\0"s), std::nullopt);
    EXPECT_EQ(removedDevice("remove@/x\0MAJOR=81\0"s), std::nullopt);
    EXPECT_EQ(removedDevice("libudev\0\xfe\xed\xca\xfe"s), std::nullopt); // udevd's own format (group 2)
    EXPECT_EQ(removedDevice(""), std::nullopt);
}

TEST(DeviceRemovalWatch, NothingWaitingIsNoRemoval)
{
    DeviceRemovalWatch watch;
    if (watch.fd() < 0)
        GTEST_SKIP() << "no uevent socket here (a sandbox without netlink)";
    EXPECT_FALSE(watch.takeRemoval({makedev(81, 2)})); // returns at once: the socket never blocks
}

} // namespace
} // namespace overlayd