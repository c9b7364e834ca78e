// SPDX-License-Identifier: Apache-2.0
#include "control/http_front.h"

#include "base/utf8.h"

namespace overlayd {

namespace {

constexpr size_t kMaxLoggedBodyBytes = 512; // of a change's request and answer, in its log line

JpegFeed &feedOrAbort(std::unique_ptr<JpegFeed> &feed)
{
    if (!feed) {
        auto created = JpegFeed::create();
        // An eventfd that cannot be made means the process is out of fds at start-up: nothing else would work.
        if (!created)
            std::abort();
        feed = std::move(*created);
    }
    return *feed;
}

} // namespace

HttpFront::HttpFront(Logger &logger, SceneControl &scene, const DaemonStatus &status)
    : logger_(logger), api_(scene, status, [this] { return server_ ? server_->counters() : HttpCounters{}; }),
      rawTap_(feedOrAbort(feed_), quality_)
{}

HttpFront::~HttpFront()
{
    removeFromLoop();
}

Result<std::unique_ptr<HttpServer>> HttpFront::startServer(const HttpOptions &options)
{
    return HttpServer::start(
        options, *feed_,
        [this](const HttpRequest &request) {
            HttpResponse response = api_.handle(request);
            logChange(request, response);
            return response;
        },
        logger_);
}

void HttpFront::logChange(const HttpRequest &request, const HttpResponse &response)
{
    // A change (PUT) or a save, whoever made it and what it was; a refused one at info, with why.
    const bool save = request.method == "POST" && request.path == "/api/save";
    if (request.method != "PUT" && !save)
        return;
    const std::string what = cat(request.peer, " ", request.method, " ", request.path,
                                 save ? std::string() : " " + quotable(request.body, kMaxLoggedBodyBytes));
    std::string_view answer = response.body;
    while (!answer.empty() && answer.back() == '\n')
        answer.remove_suffix(1);
    if (response.status == 200)
        logger_.notice(cat("http: ", what, " -> ", quotable(answer, kMaxLoggedBodyBytes)));
    else
        logger_.info(cat("http: ", what, " refused (", response.status, "): ", quotable(answer, kMaxLoggedBodyBytes)));
}

Status HttpFront::configure(const HttpOptions &options)
{
    if (options == options_ && (server_ != nullptr) == options.enabled)
        return Ok{};
    HttpOptions sameCertificate = options;
    sameCertificate.tls = options_.tls;
    if (server_ && !options.tls.empty() && sameCertificate == options_) { // renewed: open streams go on
        if (Status renewed = server_->replaceCertificate(options.tls); !renewed)
            return renewed.error();
        options_ = options;
        logger_.notice("http: the TLS certificate was renewed (" + options.tlsCert + ")");
        return Ok{};
    }
    if (!timeout_) {
        for (auto *timer : {&timeout_, &tick_}) {
            auto created = Timer::create();
            if (!created)
                return created.error();
            timer->emplace(std::move(*created));
        }
    }
    // The old server lets go of its address first: the new one usually listens on the same.
    const HttpOptions previous = options_;
    const bool wasRunning = server_ != nullptr;
    removeFromLoop();
    server_.reset();
    if (options.enabled) {
        auto started = startServer(options);
        if (!started) {
            if (wasRunning)
                if (auto again = startServer(previous))
                    server_ = std::move(*again);
            addToLoop();
            return started.error();
        }
        server_ = std::move(*started);
        logger_.notice(cat("http: serving on ", options.tls.empty() ? "http" : "https", "://",
                           server_->address().describe(), "/"));
    }
    options_ = options;
    quality_ = options.jpegQuality;
    addToLoop();
    return Ok{};
}

void HttpFront::attachLoop(EventLoop *loop)
{
    removeFromLoop();
    loop_ = loop;
    addToLoop();
}

void HttpFront::addToLoop()
{
    if (!loop_ || !server_)
        return;
    watchedFd_ = server_->fd();
    (void)loop_->add(watchedFd_, [this] { pump(); });
    (void)loop_->add(timeout_->fd(), [this] {
        timeout_->consume();
        pump();
    });
    (void)loop_->add(tick_->fd(), [this] {
        tick_->consume();
        server_->onTick();
        pump();
    });
    (void)loop_->add(feed_->wakeFd(), [this] {
        server_->onJpeg();
        pump();
    });
    (void)tick_->arm(std::chrono::seconds(1), std::chrono::seconds(1));
    pump();
}

void HttpFront::removeFromLoop()
{
    if (!loop_ || watchedFd_ < 0)
        return;
    loop_->remove(watchedFd_);
    loop_->remove(timeout_->fd());
    loop_->remove(tick_->fd());
    loop_->remove(feed_->wakeFd());
    tick_->disarm();
    timeout_->disarm();
    watchedFd_ = -1;
}

void HttpFront::pump()
{
    server_->run();
    // libmicrohttpd's next deadline (connection timeouts); at least a millisecond, so that a zero does not spin.
    if (const auto timeout = server_->timeout())
        (void)timeout_->arm(std::max(*timeout, std::chrono::milliseconds(1)));
    else
        timeout_->disarm();
}

SinkOptions HttpFront::sinkOptions()
{
    SinkOptions options;
    options.name = "http";
    options.path = "http";
    options.queueDepth = 1; // the newest frame is the one worth encoding
    options.dropPolicy = DropPolicy::DropOldest;
    return options;
}

std::unique_ptr<FrameSink> HttpFront::makeSink()
{
    return std::make_unique<JpegFeedSink>(*feed_, quality_);
}

} // namespace overlayd
