#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""An RTSP server in RECORD mode (ANNOUNCE/SETUP/RECORD), for the push test: gst-rtsp-server with a media factory
whose pipeline depayloads what a client pushes and writes it as an H.264 byte stream to a file, which the test then
decodes with ffmpeg (independent of GStreamer and of overlayd's encoder).

    rtsp_record_server.py PORT MOUNT OUT.h264 SECONDS
Prints "listening" once it accepts connections; exits after SECONDS. Needs python3-gi and
gir1.2-gst-rtsp-server-1.0; exit status 3 when they are missing (the test says SKIP with the reason)."""
import sys

try:
    import gi

    gi.require_version("Gst", "1.0")
    gi.require_version("GstRtspServer", "1.0")
    from gi.repository import GLib, Gst, GstRtspServer
except (ImportError, ValueError) as missing:
    print(f"missing: {missing}", flush=True)
    sys.exit(3)


def main():
    port, mount, out, seconds = sys.argv[1], sys.argv[2], sys.argv[3], float(sys.argv[4])
    Gst.init(None)
    server = GstRtspServer.RTSPServer.new()
    server.set_address("127.0.0.1")
    server.set_service(port)
    factory = GstRtspServer.RTSPMediaFactory.new()
    factory.set_transport_mode(GstRtspServer.RTSPTransportMode.RECORD)
    # depay0: the name record mode looks for. Access units as they arrived, parameter sets before each keyframe.
    factory.set_launch("( rtph264depay name=depay0 ! h264parse config-interval=-1 ! "
                       "video/x-h264,stream-format=byte-stream,alignment=au ! "
                       f"filesink location={out} async=false sync=false buffer-mode=unbuffered )")
    server.get_mount_points().add_factory(mount, factory)
    if server.attach(None) == 0:
        print(f"cannot listen on 127.0.0.1:{port}", flush=True)
        return 1
    print("listening", flush=True)
    loop = GLib.MainLoop()
    GLib.timeout_add(int(seconds * 1000), loop.quit)
    loop.run()
    return 0


if __name__ == "__main__":
    sys.exit(main())
