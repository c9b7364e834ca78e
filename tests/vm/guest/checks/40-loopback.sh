# SPDX-License-Identifier: Apache-2.0
# Loopback proof: overlayd captures vivid instance 0 (black pattern) and writes the overlaid stream to instance
# 1's HDMI output, which vivid loops back (loop_video=1) to instance 1's HDMI capture input. v4l2-ctl reads the
# looped frames: the axes must be where `overlayd project` puts them, so the overlay went through a real kernel
# output driver, and the privacy masks must be there too. v4l2-compliance then streams the same looped node as an
# independent client.
. /vm/lib.sh

have_overlayd || { fail loopback "no overlayd binary was staged (build the overlayd target)"; exit 0; }
vivid_hdmi_loop || { fail loopback "modprobe vivid failed"; exit 0; }
loop_overlay_run loopback loopback.toml ""
summary=''
mask_check /tmp/loopback.yuv /tmp/loopback.toml
verdict loopback-mask $? "privacy masks in the frame looped back from $OUT, filled before the sink saw it:$summary"

# v4l2-compliance as an independent client of the frames we write: its streaming tests (MMAP with select and
# epoll: sequence numbers, timestamps, field, bytesused) on the looped capture node while overlayd feeds the
# output. Only those lines decide: the rest of its report is about vivid (v4l-utils 1.22 disagrees with kernel 6.1
# on some format descriptions) and is printed for information. It runs last: its control tests press vivid's
# "Disconnect" button, after which the output node returns ENODEV.
timeout 120 v4l2-compliance -d "$CAP" -s 10 >/tmp/compliance.log 2>&1
streaming=$(tr '\r' '\n' </tmp/compliance.log | grep -o 'test MMAP.*: [A-Z]*')
[ -n "$streaming" ] && ! echo "$streaming" | grep -v -q ': OK'
verdict loopback-compliance $? "v4l2-compliance -s on $CAP while overlayd writes $OUT: $(echo "$streaming" |
    tr '\n' ';') (all of its report: $(grep '^Total' /tmp/compliance.log | tail -1))"
grep -E 'fail:' /tmp/compliance.log | sort | uniq -c | head -5

stop_overlayd $pid
rc=$?
[ $rc = 0 ]
verdict loopback-exit $rc "overlayd run exited with $rc after SIGTERM"
tail -5 /tmp/loopback-run.log
rmmod vivid
exit 0
