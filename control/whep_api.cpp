// SPDX-License-Identifier: Apache-2.0
// WHEP: the engine's errors become the statuses the draft names (400 a bad offer, 503 when full or not running).
#include "control/whep_api.h"

namespace overlayd {
namespace {

HttpResponse fromError(const Error &error)
{
    switch (error.code) {
    case ErrorCode::Malformed:
    case ErrorCode::InvalidArgument:
        return HttpResponse::error(400, error.message);
    case ErrorCode::NotFound:
        return HttpResponse::error(404, error.message);
    case ErrorCode::Unsupported:
        return HttpResponse::error(404, error.message);
    default: // full, not running yet, no answer in time
        return HttpResponse::error(503, error.message);
    }
}

} // namespace

bool isWhepPath(const std::string &path)
{
    return path == kWhepPath ||
           (path.starts_with(kWhepPath) && path.size() > kWhepPath.size() + 1 && path[kWhepPath.size()] == '/');
}

HttpResponse handleWhep(const DaemonStatus &status, const HttpRequest &request)
{
    const bool collection = request.path == kWhepPath;
    if (collection && request.method != "POST")
        return HttpResponse::error(405, "POST /whep with an SDP offer (application/sdp)");
    if (!collection && request.method != "DELETE")
        return HttpResponse::error(405, "DELETE /whep/ID hangs up");
    const auto stream = status.encodedStream();
    if (!stream || !stream->options().webrtc.enabled)
        return HttpResponse::error(404, "WebRTC is off ([webrtc] enabled = true turns it on)");
    if (!collection) {
        const std::string id = request.path.substr(kWhepPath.size() + 1);
        if (auto removed = stream->removePeer(id); !removed)
            return fromError(removed.error());
        HttpResponse response;
        response.body = "{}\n";
        return response;
    }
    const std::string type = request.contentType.substr(0, request.contentType.find(';'));
    if (type != "application/sdp")
        return HttpResponse::error(415, "Content-Type: the offer is application/sdp, not '" + type + "'");
    auto answer = stream->addPeer(request.body, request.peer);
    if (!answer)
        return fromError(answer.error());
    HttpResponse response;
    response.status = 201;
    response.contentType = "application/sdp";
    response.body = std::move(answer->sdp);
    response.headers.emplace_back("Location", std::string(kWhepPath) + "/" + answer->id);
    return response;
}

} // namespace overlayd
