# SPDX-License-Identifier: Apache-2.0
# vivid itself, with v4l2-ctl as the client: the driver streams the sizes the overlayd checks use, so a failure
# in the later checks is ours, not the driver's.
. /vm/lib.sh

vivid_load n_devs=1 node_types=0x1 multiplanar=1 || { fail vivid-load "modprobe vivid failed"; exit 0; }
pass vivid-load "$(cat /sys/class/video4linux/video0/name) on /dev/video0"
for wh in 640x480 1280x720; do
    w=${wh%x*} h=${wh#*x}
    v4l2-ctl -d /dev/video0 --set-fmt-video=width=$w,height=$h,pixelformat=YUYV &&
        v4l2-ctl -d /dev/video0 --stream-mmap=4 --stream-count=5 --stream-to=/tmp/v.yuv >/dev/null 2>&1
    size=$(wc -c </tmp/v.yuv)
    [ "$size" = $((w * h * 2 * 5)) ]
    verdict "vivid-v4l2ctl-$wh" $? "v4l2-ctl captured 5 YUYV frames: $size bytes (want $((w * h * 2 * 5)))"
    rm -f /tmp/v.yuv
done
exit 0
