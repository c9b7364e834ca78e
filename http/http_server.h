// SPDX-License-Identifier: Apache-2.0
// HttpServer: libmicrohttpd in its epoll mode, driven by the daemon's event loop (no thread per client; streams
// and snapshot waits are suspended connections resumed when a JPEG is published). It serves the stream, snapshots
// and the page itself and hands every other request to the daemon's API handler, after the control check.
#pragma once

#include <array>
#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "base/auth_failures.h"
#include "base/logger.h"
#include "base/result.h"
#include "http/credentials.h"
#include "http/http_options.h"
#include "http/jpeg_feed.h"
#include "http/listen_address.h"
#include "http/request_slots.h"

struct MHD_Daemon;
struct MHD_Connection;

namespace overlayd {

struct HttpRequest {
    std::string method;
    std::string path; // without the query
    std::map<std::string, std::string> query;
    std::string body;
    std::string peer;
    std::string contentType; // of the body, as sent
};

struct HttpResponse {
    unsigned status = 200;
    std::string contentType = "application/json";
    std::string body;
    std::vector<std::pair<std::string, std::string>> headers;

    static HttpResponse json(unsigned status, std::string body);
    // The longest error message an answer quotes, in bytes (cut on a character boundary).
    static constexpr size_t kMaxErrorBytes = 4096;

    // {"error": message}: valid JSON whatever the message holds (bytes that are not UTF-8 and control characters
    // written as \xNN).
    static HttpResponse error(unsigned status, const std::string &message);
};

// A Digest challenge libmicrohttpd adds to a 401 (with a nonce of its own making): none, a fresh one, or one that
// says the client's nonce was only too old (stale).
enum class DigestChallenge { None, Fresh, Stale };

// The daemon's endpoints (/state, /metrics, /api/...), called on the loop thread.
using ApiHandler = std::function<HttpResponse(const HttpRequest &)>;

struct HttpCounters {
    unsigned connections = 0;      // open now
    unsigned streamClients = 0;    // of which /stream
    uint64_t requests = 0;         // answered since start
    uint64_t partsSent = 0;        // JPEG parts written to /stream clients
    uint64_t refused = 0;          // 4xx/5xx answers
    std::vector<double> streamFps; // each /stream client's recent parts per second
    // How often each limit was hit: {name in /metrics, count} (docs/config.md "Limits" names them).
    std::vector<std::pair<std::string, uint64_t>> limits;
};

class HttpServer
{
public:
    // Listens and starts serving; the token (control = "token") is read here.
    static Result<std::unique_ptr<HttpServer>> start(const HttpOptions &options, JpegFeed &feed, ApiHandler api,
                                                     Logger &logger);
    ~HttpServer();
    HttpServer(const HttpServer &) = delete;
    HttpServer &operator=(const HttpServer &) = delete;

    // Readable when libmicrohttpd has work: the loop calls run() then.
    int fd() const;
    void run();
    // When run() must be called again at the latest (connection timeouts), nullopt: no deadline.
    std::optional<std::chrono::milliseconds> timeout() const;
    // A JPEG was published: resume the streams and snapshots waiting for it.
    void onJpeg();
    // Once a second: idle streams resend their last frame, overdue snapshot waits answer 503.
    void onTick();

    // A renewed certificate (options().tls changed, nothing else): the next handshakes get it, open connections
    // go on.
    Status replaceCertificate(const TlsFiles &files);

    const ListenAddress &address() const { return address_; }
    const HttpOptions &options() const { return options_; }
    HttpCounters counters() const;

    struct StreamClient;
    struct Exchange;
    struct Connection;

private:
    HttpServer(const HttpOptions &options, ListenAddress address, JpegFeed &feed, ApiHandler api, Logger &logger);

    friend struct MhdCallbacks; // libmicrohttpd's C callbacks, in http_server.cpp

    int access(MHD_Connection *connection, const std::string &url, const std::string &method, Exchange &exchange);
    int answer(MHD_Connection *connection, const HttpResponse &response,
               DigestChallenge challenge = DigestChallenge::None);
    int answerSnapshot(MHD_Connection *connection, Exchange &exchange);
    int startStream(MHD_Connection *connection);
    int serveFile(MHD_Connection *connection, const std::string &path);
    std::optional<HttpResponse> refuse(MHD_Connection *connection, const HttpRequest &request,
                                       DigestChallenge &challenge);
    // The role a Digest answer proves (None when it proves none; `stale` when only its nonce was too old).
    Role digest(MHD_Connection *connection, bool &stale) const;
    ssize_t fillStream(StreamClient &client, char *buffer, size_t max);
    void resumeAll();
    bool closeHungUp();
    void shed(const std::vector<std::pair<RequestSlots::Id, ShedReason>> &victims);
    unsigned maxStreams() const;

    HttpOptions options_;
    ListenAddress address_;
    JpegFeed &feed_;
    ApiHandler api_;
    Logger &logger_;
    Credentials credentials_;
    AuthFailures authFailures_{"http"};
    std::array<unsigned char, 32> digestRandom_{}; // libmicrohttpd's key for the Digest nonces it makes
    MHD_Daemon *daemon_ = nullptr;
    bool stopping_ = false;

    std::vector<MHD_Connection *> suspended_; // resumed on the next JPEG or tick
    std::vector<StreamClient *> streams_;
    std::vector<Connection *> connections_; // every open connection
    HttpCounters counters_;
    RequestSlots slots_;
    uint64_t streamsRefused_ = 0; // /stream over max_streams
    bool shed_ = false;           // shed() shut a connection down since the last pass of run()
};

} // namespace overlayd
