# SPDX-License-Identifier: Apache-2.0
# The verdict: the guest's PASS/FAIL lines, host-side checks of what the guest produced (ffprobe reads the Y4M
# files as an independent client), and the harness's own failures (module build, a guest that never finished).
# shellcheck shell=bash

vmHostCheck() { # NAME STATUS DETAIL
    if [ "$2" = 0 ]; then echo "PASS $1: $3"; else echo "FAIL $1: $3"; fi
}

# ffprobe must agree with the name the guest gave the file: capture-<api>-<format>-<W>x<H>.y4m, 3 frames.
vmFfprobeArtifacts() {
    local file name size fmt want got
    for file in "$VM_WORK"/share/out/capture-*.y4m; do
        [ -e "$file" ] || continue
        name=$(basename "$file" .y4m)
        size=${name##*-} fmt=$(echo "$name" | cut -d- -f3)
        case $fmt in YUYV) want=yuv422p ;; NV12) want=yuv420p ;; *) want=yuv444p ;; esac
        got=$(ffprobe -v error -count_frames -select_streams v:0 \
            -show_entries stream=width,height,pix_fmt,nb_read_frames -of csv=p=0 "$file" 2>&1 | head -1)
        [ "$got" = "${size%x*},${size#*x},$want,3" ]
        vmHostCheck "ffprobe-$name" $? "ffprobe reads $got (want ${size%x*},${size#*x},$want,3)"
    done
    # The first megabytes of each /stream (checks/80-http-ustreamer.sh): multipart JPEG parts at 1280x720.
    for file in "$VM_WORK"/share/out/http-*.mjpg; do
        [ -e "$file" ] || continue
        name=$(basename "$file" .mjpg)
        got=$(ffprobe -v error -f mpjpeg -select_streams v:0 -show_entries stream=codec_name,width,height \
            -of csv=p=0 "$file" 2>&1 | head -1)
        [ "$got" = "mjpeg,1280,720" ]
        vmHostCheck "ffprobe-$name" $? "ffprobe -f mpjpeg reads $got (want mjpeg,1280,720)"
    done
}

# checks/90-can-steering.sh kept /snapshot JPEGs for steering angles A and B, stale and out of range: the wheel tracks
# must lie where the host's own Ackermann geometry, projected by `overlayd project` (this overlayd, the config the
# guest ran), puts them (host/can_steering.py: python3's standard library and ffmpeg).
vmCanSteeringArtifacts() {
    local overlayd=$1 out=$VM_WORK/share/out
    [ -e "$out/can-steering-angles.txt" ] || [ -e "$out/can-steering-a.jpg" ] || return 0
    python3 "$VM_HERE/host/can_steering.py" "$out" "$overlayd" "$out/can-steering.toml" 2>&1 ||
        vmHostCheck can-steering-host 1 "host/can_steering.py failed (exit $?)"
}

# Prints the summary; returns 0 if every check passed and the guest finished.
vmReport() {
    local log=$1 boot_status=$2 overlayd=$3 lines
    lines=$(
        grep -a -E '^(PASS|FAIL) ' "$log" | tr -d '\r'
        [ "$VM_MODULES_OK" = 1 ] || vmHostCheck host-module-build 1 "out-of-tree modules did not build (see above)"
        [ -x "$overlayd" ] || vmHostCheck host-overlayd 1 "no overlayd binary at $overlayd (build the overlayd target)"
        grep -a -q '== VM DONE' "$log" ||
            vmHostCheck guest-finished 1 "the guest did not finish (QEMU status $boot_status); see $log"
        vmFfprobeArtifacts
        vmCanSteeringArtifacts "$overlayd"
    )
    echo "$lines"
    local measures failed passed
    measures=$(grep -a '^MEASURE ' "$log" | tr -d '\r' || true) # figures for the docs, counted neither way
    [ -z "$measures" ] || echo "$measures"
    failed=$(echo "$lines" | grep -c '^FAIL ' || true)
    passed=$(echo "$lines" | grep -c '^PASS ' || true)
    # A run of measuring checks alone (--checks 65-source-cost) has no verdicts: its figures are what it proves.
    if [ "$failed" != 0 ] || { [ "$passed" = 0 ] && [ -z "$measures" ]; }; then
        echo "VM TIER FAILED: $failed of $((passed + failed)) checks failed"
        [ "$passed" = 0 ] && tail -40 "$log"
        return 1
    fi
    echo "VM TIER PASSED: $passed checks${measures:+, $(echo "$measures" | wc -l) measurement(s)}"
}
