# SPDX-License-Identifier: Apache-2.0
# Zero copy through real drivers: overlayd captures vivid instance 0 and queues the very capture buffers it blended
# into on instance 1's HDMI output (zero_copy = "on": VIDIOC_EXPBUF on the capture, V4L2_MEMORY_DMABUF on the
# output), which vivid loops back to instance 1's capture node. The looped frames must carry the overlay where
# `overlayd project` says, and overlayd must report every frame it wrote as zero-copy. A baseline first: v4l2-ctl
# drives the same path (capture MMAP, exported buffers queued on the output by DMABUF), so that a refusal is
# vivid's and is named as such.
. /vm/lib.sh

have_overlayd || { fail zerocopy "no overlayd binary was staged (build the overlayd target)"; exit 0; }
vivid_hdmi_loop || { fail zerocopy "modprobe vivid failed"; exit 0; }

v4l2-ctl -d "$SRC" --set-fmt-video=width=$W,height=$H,pixelformat=YUYV
v4l2-ctl -d "$OUT" --set-fmt-video-out=width=$W,height=$H,pixelformat=YUYV
timeout 60 v4l2-ctl -d "$SRC" -e "$OUT" --stream-mmap=4 --stream-out-dmabuf --stream-count=8 >/tmp/zc-base.log 2>&1
# v4l2-ctl exits 0 whatever happened: its progress marks decide ('<' a frame captured, '>' a buffer output).
caps=$(tr -cd '<' </tmp/zc-base.log | wc -c) outs=$(tr -cd '>' </tmp/zc-base.log | wc -c)
[ "$outs" -ge 4 ] && ! grep -q 'failed' /tmp/zc-base.log
verdict zerocopy-vivid-dmabuf $? "v4l2-ctl: $SRC MMAP capture, buffers exported and queued on $OUT by DMABUF: \
$caps captured, $outs output; $(grep -m1 'failed' /tmp/zc-base.log)"
cp /tmp/zc-base.log "$ART/zerocopy-v4l2ctl.log"

loop_overlay_run zerocopy zerocopy.toml ", zero_copy = on"
summary=''
mask_check /tmp/zerocopy.yuv /tmp/zerocopy.toml
verdict zerocopy-mask $? "privacy masks in the frame looped back from $OUT, filled before the sink saw it:$summary"

stop_overlayd $pid
rc=$?
# The sink's own account at close: "<device>: N frames out: Z zero-copy, C copied, D dropped".
counts=$(sed -n 's/.*: \([0-9]*\) frames out: \([0-9]*\) zero-copy, \([0-9]*\) copied, \([0-9]*\) dropped.*/\1 \2 \3 \4/p' \
    /tmp/zerocopy-run.log | tail -1)
set -- $counts 0 0 0 0
stats=$(grep -c ' zero-copy; \| zero-copy$' /tmp/zerocopy-run.log)
[ $rc = 0 ] && grep -q 'zero copy: the capture buffers are queued by DMABUF' /tmp/zerocopy-run.log &&
    [ "$1" -gt 0 ] && [ "$2" = "$1" ] && [ "$3" = 0 ] && [ "$stats" -gt 0 ]
verdict zerocopy-log $? "exit $rc; $1 frames out: $2 zero-copy, $3 copied, $4 dropped; $stats stats lines with a \
zero-copy count"
grep -E 'v4l2|zero|stats' /tmp/zerocopy-run.log | tail -4
rmmod vivid
exit 0
