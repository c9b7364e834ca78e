// SPDX-License-Identifier: Apache-2.0
// checkListenable: whether an RTSP sink's address can be listened on, asked by the config loader so that
// check-config, run and a reload refuse a taken port at its key, as the engine's server would when it binds.
#pragma once

#include <string>

#include "base/result.h"

namespace overlayd {

// A TCP socket bound to HOST:PORT (SO_REUSEADDR, as gst-rtsp-server binds) and closed at once. A port already
// listened on is taken only by another program: one held by this process (the running engine, which a reload
// takes over) or by another overlayd (the running daemon, when check-config is asked before a reload) passes.
// The holder is found through /proc/net/tcp{,6} and /proc/PID/fd; its name is in the message.
Status checkListenable(const std::string &host, unsigned port);

} // namespace overlayd
