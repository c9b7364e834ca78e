// SPDX-License-Identifier: Apache-2.0
// WHEP (WebRTC-HTTP egress): POST /whep with an SDP offer answers 201 with the SDP answer and the peer's Location;
// DELETE /whep/ID hangs it up. The engine does the WebRTC (encoded_stream_engine.h); this is the HTTP side.
#pragma once

#include "control/daemon_status.h"
#include "http/http_server.h"

namespace overlayd {

inline constexpr std::string_view kWhepPath = "/whep";

// Whether `path` is WHEP's (/whep or /whep/ID).
bool isWhepPath(const std::string &path);
// On the loop thread; POST waits for the answer, at most kWhepAnswerTimeout.
HttpResponse handleWhep(const DaemonStatus &status, const HttpRequest &request);

} // namespace overlayd
