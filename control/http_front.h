// SPDX-License-Identifier: Apache-2.0
// HttpFront: the daemon's HTTP side. It owns the JPEG feed, the server and the API, wires the server into the
// event loop (its epoll fd, a timeout timer, a one-second tick, the feed's wake-up fd) and makes the sink that
// encodes the stream. The scene changes it asks for go through SceneControl like every other change.
#pragma once

#include <atomic>
#include <memory>
#include <optional>

#include "base/event_loop.h"
#include "control/http_api.h"
#include "control/http_frames.h"
#include "drivers/sink_options.h"
#include "http/http_server.h"

namespace overlayd {

class HttpFront
{
public:
    HttpFront(Logger &logger, SceneControl &scene, const DaemonStatus &status);
    ~HttpFront();

    // Starts the server, restarts it when the options changed, or stops it (options.enabled false). A server that
    // cannot start (the port is taken, the token unreadable) is an error, and the server that ran keeps running.
    Status configure(const HttpOptions &options);
    bool running() const { return server_ != nullptr; }
    // Adds the server's fds to the loop (null: removes them).
    void attachLoop(EventLoop *loop);

    // The sink that encodes the overlaid stream for the feed (one JPEG per frame, only while wanted), and the
    // options of the worker the daemon runs it on.
    std::unique_ptr<FrameSink> makeSink();
    static SinkOptions sinkOptions();
    // The pipeline's tap before the overlay, for raw snapshots.
    void onRawFrame(const FrameView &frame, const FrameMetadata &metadata) { rawTap_(frame, metadata); }

private:
    Result<std::unique_ptr<HttpServer>> startServer(const HttpOptions &options);
    // The log line of a control request that changes something (PUT, POST /api/save): who and what.
    void logChange(const HttpRequest &request, const HttpResponse &response);
    void addToLoop();
    void removeFromLoop();
    void pump(); // libmicrohttpd's work, then its next deadline on the timer

    Logger &logger_;
    std::atomic<int> quality_{80};
    std::unique_ptr<JpegFeed> feed_;
    std::optional<Timer> timeout_, tick_;
    HttpApi api_;
    RawSnapshotTap rawTap_;
    std::unique_ptr<HttpServer> server_;
    HttpOptions options_;
    EventLoop *loop_ = nullptr;
    int watchedFd_ = -1; // the server's epoll fd while in the loop
};

} // namespace overlayd
