# SPDX-License-Identifier: Apache-2.0
# The V4L2 M2M encoder path through a real driver: overlayd captures vivid (black), draws the axes and encodes the
# blended frames with vicodec's stateful encoder (codec = "fwht", encoder = "v4l2": GStreamer's v4l2fwhtenc, the
# element family that drives a Raspberry Pi's bcm2835-codec as v4l2h264enc) into a kind = "file" sink. The file is
# then decoded by vicodec's stateful decoder driven by v4l2-ctl, an independent client, and the decoded frames must
# carry the axis colours where `overlayd project` says. Zero copy ([encoder] zero_copy = "on"): vivid's I420 buffers
# are exported (VIDIOC_EXPBUF) and queued on vicodec's OUTPUT queue by DMABUF (output-io-mode dmabuf-import), and
# overlayd's own account at close must say every frame went so, none copied.
. /vm/lib.sh

have_overlayd || { fail m2m-encode "no overlayd binary was staged (build the overlayd target)"; exit 0; }
[ -e /usr/bin/overlayd-stream.so ] ||
    { fail m2m-encode "no overlayd-stream.so was staged (a build with -DOVERLAYD_STREAM=ON has it)"; exit 0; }
vivid_load n_devs=1 node_types=0x1 multiplanar=1 || { fail m2m-encode "modprobe vivid failed"; exit 0; }
modprobe vicodec || { fail m2m-encode "modprobe vicodec failed"; exit 0; }
SRC=$(node vivid-000-vid-cap) ENC=$(node stateful-encoder) DEC=$(node stateful-decoder)
black_pattern "$SRC"
W=640 H=480 FWHT=/tmp/m2m.fwht YUV=/tmp/m2m-decoded.yuv
mkdir -p "$ART"

config_for m2m-encode.toml /tmp/m2m.toml "device=\"$SRC\""
# vb2's reasons for refusing a buffer (a DMABUF it cannot import) into the kernel log, kept as an artifact.
echo 1 >/sys/module/videobuf2_common/parameters/debug 2>/dev/null
rm -f "$FWHT"
# GStreamer's warnings into the log kept as an artifact: a refused negotiation names the caps there.
GST_DEBUG=2 overlayd run --config /tmp/m2m.toml >/tmp/m2m-run.log 2>&1 &
pid=$!
# Under TCG the first frames take a few seconds (GStreamer's registry scan, the encoder's start).
wait_for 60 sh -c "[ \$(wc -c <$FWHT 2>/dev/null || echo 0) -gt 200000 ]"
grown=$?
stop_overlayd $pid
rc=$?
size=$(wc -c <"$FWHT" 2>/dev/null || echo 0)
[ $grown = 0 ] && [ $rc = 0 ] && grep -q 'v4l2fwhtenc' /tmp/m2m-run.log
verdict m2m-encode $? "overlayd run exit $rc, $size bytes of FWHT from $ENC; \
$(grep -m1 -o 'fwht to .*' /tmp/m2m-run.log) \
$(grep -m2 -i 'error\|refus' /tmp/m2m-run.log | tr '\n' ' ')"
cp /tmp/m2m-run.log "$ART/m2m-run.log"
dmesg >"$ART/m2m-dmesg.log" 2>/dev/null
echo 0 >/sys/module/videobuf2_common/parameters/debug 2>/dev/null
# The encoded stream's account at close: "encoder <element>: N frames in: Z zero-copy, C copied, D dropped".
set -- $(sed -n 's/.*encoder v4l2fwhtenc: \([0-9]*\) frames in: \([0-9]*\) zero-copy, \([0-9]*\) copied, \([0-9]*\) dropped.*/\1 \2 \3 \4/p' \
    /tmp/m2m-run.log | tail -1)
[ "${1:-0}" -ge 10 ] && [ "$2" = "$1" ] && [ "$3" = 0 ] && [ $grown = 0 ]
verdict m2m-zerocopy $? "$1 frames in: $2 zero-copy (DMABUF import), $3 copied, $4 dropped; \
$(grep -m2 -i 'zero_copy\|dmabuf' /tmp/m2m-run.log | tr '\n' ' ')"

# vicodec's decoder takes the stream's format from each frame's header; v4l2-ctl splits the file at the FWHT
# magic and follows the decoder's source change to the capture format (YU12: I420, as the daemon fed it).
timeout 120 v4l2-ctl -d "$DEC" --set-fmt-video-out=pixelformat=FWHT --stream-out-mmap --stream-mmap \
    --stream-from="$FWHT" --stream-to="$YUV" >/tmp/m2m-decode.log 2>&1
fourcc=$(v4l2-ctl -d "$DEC" --get-fmt-video | sed -n "s/.*Pixel Format[^']*'\([^']*\)'.*/\1/p")
frame=$((W * H * 3 / 2))
frames=$(($(wc -c <"$YUV" 2>/dev/null || echo 0) / frame))
# i420_pixel K X Y: "Y Cb Cr" of pixel (X, Y) of decoded frame K
i420_pixel() {
    base=$(($1 * frame)) cx=$(($2 / 2)) cy=$(($3 / 2))
    echo "$(bytes_at "$YUV" $((base + $3 * W + $2)) 1) $(bytes_at "$YUV" $((base + W * H + cy * W / 2 + cx)) 1)" \
        "$(bytes_at "$YUV" $((base + W * H + W * H / 4 + cy * W / 2 + cx)) 1)"
}
PIXEL="i420_pixel $((frames - 1))"
axes_check "$(axes_points /tmp/m2m.toml)"
axes=$?
[ "$frames" -ge 2 ] && [ "$fourcc" = YU12 ] && [ $axes = 0 ]
verdict m2m-decode $? "v4l2-ctl on $DEC: $frames frames ${W}x$H $fourcc decoded; last frame:$summary"
cp "$FWHT" "$ART/m2m.fwht" 2>/dev/null
tail -3 /tmp/m2m-decode.log
rmmod vicodec v4l2-mem2mem vivid 2>/dev/null
exit 0
