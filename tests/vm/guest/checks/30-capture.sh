# SPDX-License-Identifier: Apache-2.0
# overlayd render captures from vivid in YUYV, NV12 and RGB24 at 640x480 and 1280x720, through the single- and
# the multi-planar API, with an overlay: the Y4M stream has the right header and size, the driver was set to the
# asked format (v4l2-ctl reads it back), and the axes are where `overlayd project` puts them.
. /vm/lib.sh

FRAMES=3
have_overlayd || { fail capture "no overlayd binary was staged (build the overlayd target)"; exit 0; }
mkdir -p "$ART"

# expected Y4M chroma tag and V4L2 fourccs (single- or multi-planar variant) per format
chroma_of() { case $1 in YUYV) echo 422 ;; NV12) echo 420jpeg ;; RGB24) echo 444 ;; esac; }
fourccs_of() { case $1 in YUYV) echo "YUYV" ;; NV12) echo "NV12 NM12" ;; RGB24) echo "RGB3" ;; esac; }

capture_case() { # API FORMAT W H
    name=capture-$1-$2-${3}x$4 cfg=/tmp/$name.toml out=/tmp/$name.y4m points=/tmp/points-${3}x$4
    config_for capture.toml "$cfg" "format=\"$2\"" "width=$3" "height=$4" "device=\"$DEV\""
    if ! overlayd render --config "$cfg" --frames $FRAMES --output "$out" >/tmp/$name.log 2>&1; then
        fail "$name" "overlayd render exited non-zero: $(tail -3 /tmp/$name.log | tr '\n' ' ')"
        return
    fi
    set -- $(y4m_geometry "$out")
    want=$(($4 + FRAMES * ($5 + 6)))
    size=$(wc -c <"$out")
    fourcc=$(v4l2-ctl -d "$DEV" --get-fmt-video | sed -n "s/.*Pixel Format[^']*'\([^']*\)'.*/\1/p")
    [ -s "$points" ] || axes_points "$cfg" >"$points"
    PIXEL="y4m_pixel $out $((FRAMES - 1))"
    axes_check "$(cat "$points")"
    axes=$?
    [ "$1x$2" = "${name##*-}" ] && [ "$3" = "$(chroma_of "$FMT")" ] && [ "$size" = "$want" ] &&
        echo " $(fourccs_of "$FMT") " | grep -q " $fourcc " && [ $axes = 0 ]
    verdict "$name" $? "Y4M ${1}x$2 C$3 $size bytes (want ${name##*-} C$(chroma_of "$FMT") $want); device fourcc $fourcc; axes:$summary"
    cp "$out" "$ART/" 2>/dev/null
    rm -f "$out"
}

for api in single multi; do
    [ $api = single ] && mp=1 || mp=2
    vivid_load n_devs=1 node_types=0x1 multiplanar=$mp || { fail "capture-$api" "modprobe vivid failed"; continue; }
    DEV=$(node vivid-000-vid-cap)
    black_pattern "$DEV"
    # multiplanar=2 offers only the _MPLANE buffer types: a source that used the single-planar API would fail.
    caps=$(v4l2-ctl -d "$DEV" -D | sed -n '/Device Caps/,$p' | grep -o 'Video Capture[ A-Za-z]*' | head -1)
    [ "$caps" = "Video Capture$([ $api = multi ] && echo ' Multiplanar')" ]
    verdict "capture-$api-api" $? "vivid multiplanar=$mp: device caps say '$caps'"
    for FMT in YUYV NV12 RGB24; do
        for wh in 640x480 1280x720; do capture_case $api $FMT ${wh%x*} ${wh#*x}; done
    done
done
rmmod vivid
exit 0
