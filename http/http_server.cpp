// SPDX-License-Identifier: Apache-2.0
// The server's libmicrohttpd side: request bodies within their limit, the control check, snapshot waits and MJPEG
// streams as suspended connections, and every answer with the headers a browser should see.
#include "http/http_server.h"

#include <arpa/inet.h>
#include <cstdarg>
#include <cstring>
#include <exception>
#include <fstream>
#include <microhttpd.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/random.h>
#include <sys/socket.h>

#include "http/page_files.h"
#include "http/percent_decoding.h"
#include "http/tls_certificate.h"

namespace overlayd {

namespace {

using Clock = std::chrono::steady_clock;

constexpr const char *kBoundary = "overlaydframe";
constexpr auto kIdleResend = std::chrono::seconds(1);   // an idle stream repeats its last frame this often
constexpr auto kSnapshotWait = std::chrono::seconds(3); // then /snapshot answers 503
constexpr size_t kStreamBlockBytes = 64 * 1024;         // what libmicrohttpd asks the stream for at once

std::string peerOf(MHD_Connection *connection)
{
    const MHD_ConnectionInfo *info = MHD_get_connection_info(connection, MHD_CONNECTION_INFO_CLIENT_ADDRESS);
    if (!info || !info->client_addr)
        return "unix";
    char text[INET6_ADDRSTRLEN] = "?";
    if (info->client_addr->sa_family == AF_INET)
        inet_ntop(AF_INET, &reinterpret_cast<const sockaddr_in *>(info->client_addr)->sin_addr, text, sizeof(text));
    else if (info->client_addr->sa_family == AF_INET6)
        inet_ntop(AF_INET6, &reinterpret_cast<const sockaddr_in6 *>(info->client_addr)->sin6_addr, text, sizeof(text));
    else
        return "unix";
    return text;
}

std::string header(MHD_Connection *connection, const char *name)
{
    const char *value = MHD_lookup_connection_value(connection, MHD_HEADER_KIND, name);
    return value ? value : "";
}

MHD_Result collectQuery(void *out, MHD_ValueKind, const char *key, const char *value)
{
    auto &query = *static_cast<std::map<std::string, std::string> *>(out);
    query[key ? key : ""] = value ? value : "";
    return MHD_YES;
}

} // namespace

// One TCP connection, between libmicrohttpd's "started" and "closed" notices.
struct HttpServer::Connection {
    int fd = -1;
    bool inRequest = false; // a request's headers are complete and it is not finished yet
    RequestSlots::Id id() const { return RequestSlots::Id(reinterpret_cast<uintptr_t>(this)); }
};

namespace {

HttpServer::Connection *openConnection(MHD_Connection *connection)
{
    const MHD_ConnectionInfo *info = MHD_get_connection_info(connection, MHD_CONNECTION_INFO_SOCKET_CONTEXT);
    return info ? static_cast<HttpServer::Connection *>(info->socket_context) : nullptr;
}

} // namespace

struct HttpServer::Exchange {
    std::string body;
    bool tooLarge = false;
    bool waiting = false; // suspended until a JPEG newer than afterGeneration is published
    bool raw = false;
    uint64_t afterGeneration = 0;
    Clock::time_point deadline{};
};

struct HttpServer::StreamClient {
    HttpServer *server = nullptr;
    MHD_Connection *connection = nullptr;
    std::string partHeader;
    std::shared_ptr<const JpegFrame> frame;
    size_t offset = 0; // into partHeader + frame + trailer
    bool first = true;
    uint64_t lastGeneration = 0;
    Clock::time_point nextDue{}, lastSent{};
    // parts per second over the last window, for /state
    Clock::time_point windowStart = Clock::now();
    unsigned windowParts = 0;
    double fps = 0.0;
};

struct MhdCallbacks {
    // An exception must not unwind through libmicrohttpd's C frames (that ends the process): a handler's bug is a
    // 500 answer with a JSON body, and a log line (identical ones within the logger's window are counted, not
    // printed).
    static MHD_Result access(void *self, MHD_Connection *connection, const char *url, const char *method,
                             const char *version, const char *uploadData, size_t *uploadSize, void **state)
    {
        auto &server = *static_cast<HttpServer *>(self);
        try {
            return accessUnguarded(server, connection, url, method, version, uploadData, uploadSize, state);
        } catch (const std::exception &error) {
            return failed(server, connection, error.what());
        } catch (...) {
            return failed(server, connection, "an exception that is not a std::exception");
        }
    }

    static MHD_Result failed(HttpServer &server, MHD_Connection *connection, const char *what) noexcept
    {
        try {
            server.logger_.error(std::string("http: a request failed (answered 500): ") + what);
            return MHD_Result(
                server.answer(connection, HttpResponse::error(500, std::string("internal error: ") + what)));
        } catch (...) {
            return MHD_NO; // out of memory even for the answer: libmicrohttpd closes the connection
        }
    }

    static MHD_Result accessUnguarded(HttpServer &server, MHD_Connection *connection, const char *url,
                                      const char *method, const char *, const char *uploadData, size_t *uploadSize,
                                      void **state)
    {
        HttpServer::Connection *open = openConnection(connection);
        if (!*state) {
            *state = new HttpServer::Exchange;
            if (open) {
                open->inRequest = true;
                server.slots_.phase(open->id(), RequestSlots::Phase::Body, RequestSlots::Clock::now());
            }
            // A body announced over the limit is refused before any of it is read.
            const std::string length = header(connection, MHD_HTTP_HEADER_CONTENT_LENGTH);
            if (!length.empty() && std::strtoull(length.c_str(), nullptr, 10) > kMaxBodyBytes)
                return MHD_Result(server.answer(
                    connection,
                    HttpResponse::error(413, "the body is over " + std::to_string(kMaxBodyBytes) + " bytes")));
            return MHD_YES;
        }
        auto &exchange = *static_cast<HttpServer::Exchange *>(*state);
        if (*uploadSize) {
            if (exchange.body.size() + *uploadSize > kMaxBodyBytes)
                exchange.tooLarge = true;
            else
                exchange.body.append(uploadData, *uploadSize);
            *uploadSize = 0;
            return MHD_YES;
        }
        if (open)
            server.slots_.phase(open->id(), RequestSlots::Phase::Serving, RequestSlots::Clock::now());
        return MHD_Result(server.access(connection, url ? url : "", method ? method : "", exchange));
    }

    static void completed(void *self, MHD_Connection *connection, void **state, MHD_RequestTerminationCode)
    {
        auto &server = *static_cast<HttpServer *>(self);
        if (HttpServer::Connection *open = openConnection(connection)) {
            open->inRequest = false; // a keep-alive connection waits for its next request, within the deadline
            server.slots_.phase(open->id(), RequestSlots::Phase::Headers, RequestSlots::Clock::now());
        }
        auto *exchange = static_cast<HttpServer::Exchange *>(*state);
        if (exchange && exchange->waiting)
            server.feed_.addSnapshotWaiter(exchange->raw, -1);
        delete exchange;
        *state = nullptr;
    }

    static void connection(void *self, MHD_Connection *connection, void **socketState,
                           MHD_ConnectionNotificationCode change)
    {
        auto &server = *static_cast<HttpServer *>(self);
        if (change == MHD_CONNECTION_NOTIFY_STARTED) {
            auto *open = new HttpServer::Connection;
            if (const MHD_ConnectionInfo *info = MHD_get_connection_info(connection, MHD_CONNECTION_INFO_CONNECTION_FD))
                open->fd = info->connect_fd;
            *socketState = open;
            server.connections_.push_back(open);
            ++server.counters_.connections;
            server.shed(server.slots_.opened(open->id(), peerOf(connection), RequestSlots::Clock::now()));
            return;
        }
        auto *open = static_cast<HttpServer::Connection *>(*socketState);
        server.slots_.closed(open->id());
        std::erase(server.connections_, open);
        delete open;
        *socketState = nullptr;
        if (server.counters_.connections > 0)
            --server.counters_.connections;
    }

    static ssize_t readStream(void *client, uint64_t, char *buffer, size_t max)
    {
        auto &stream = *static_cast<HttpServer::StreamClient *>(client);
        try {
            return stream.server->fillStream(stream, buffer, max);
        } catch (...) {
            return MHD_CONTENT_READER_END_WITH_ERROR; // this stream ends, the others go on
        }
    }

    static void freeStream(void *client)
    {
        auto *stream = static_cast<HttpServer::StreamClient *>(client);
        HttpServer &server = *stream->server;
        std::erase(server.streams_, stream);
        server.feed_.setWatchers(unsigned(server.streams_.size()));
        delete stream;
    }

    // The URL and the query stay as sent: access() decodes them (http/percent_decoding.h says why).
    static size_t keepEscaped(void *, MHD_Connection *, char *text) { return std::strlen(text); }

    static void log(void *self, const char *format, va_list arguments)
    {
        char text[512];
        std::vsnprintf(text, sizeof(text), format, arguments);
        std::string line = text;
        while (!line.empty() && line.back() == '\n')
            line.pop_back();
        static_cast<HttpServer *>(self)->logger_.debug("http: " + line);
    }
};

Result<std::unique_ptr<HttpServer>> HttpServer::start(const HttpOptions &options, JpegFeed &feed, ApiHandler api,
                                                      Logger &logger)
{
    auto address = parseListenAddress(options.listen);
    if (!address)
        return makeError(address.error().code, "http.listen " + address.error().message);
    if (options.control == ControlMode::Open && !address->isLocal())
        return makeError(ErrorCode::InvalidArgument,
                         "http.control = \"open\" only on loopback or a unix socket, not " + address->describe());
    std::unique_ptr<HttpServer> server(new HttpServer(options, *address, feed, std::move(api), logger));
    auto credentials = Credentials::load(options);
    if (!credentials)
        return credentials.error();
    server->credentials_ = std::move(*credentials);
    if (options.viewerOpen && !address->isLocal())
        logger.notice("http: anyone who can connect to " + address->describe() +
                      " may watch (no viewer credential: set http.viewer_token_file or http.users_file)");
    if (server->options_.pageDirectory.empty())
        server->options_.pageDirectory = defaultPageDirectory();
    unsigned flags = MHD_USE_EPOLL | MHD_ALLOW_SUSPEND_RESUME | MHD_USE_ERROR_LOG;
    if (!options.tls.empty()) {
        if (MHD_is_feature_supported(MHD_FEATURE_TLS) != MHD_YES)
            return makeError(ErrorCode::Unsupported, "http.tls_cert: this libmicrohttpd was built without TLS");
        if (Status served = server->replaceCertificate(options.tls); !served)
            return served.error();
        flags |= MHD_USE_TLS;
    } else if (!address->isLocal()) {
        logger.warning("http: listening on " + address->describe() +
                       " without TLS: the control token, viewer credentials and the video cross the network in "
                       "clear text, for anyone on the path to read and replay (set http.tls_cert and http.tls_key)");
    }
    if (getrandom(server->digestRandom_.data(), server->digestRandom_.size(), 0) !=
        ssize_t(server->digestRandom_.size()))
        return makeError(ErrorCode::Io, "http: no random bytes for the Digest nonces (getrandom)");
    auto socket = openListeningSocket(*address, kListenBacklog);
    if (!socket)
        return socket.error();
    // The certificate is asked for per handshake (TlsCertificate), so that a reload renews it in place; without TLS
    // the callback is never called.
    server->daemon_ = MHD_start_daemon(
        flags, 0, nullptr, nullptr, &MhdCallbacks::access, server.get(), MHD_OPTION_LISTEN_SOCKET, socket->get(),
        MHD_OPTION_CONNECTION_LIMIT, options.maxClients + kSpareConnections, MHD_OPTION_CONNECTION_TIMEOUT,
        kIdleTimeoutSec, MHD_OPTION_CONNECTION_MEMORY_LIMIT, kConnectionMemoryBytes, MHD_OPTION_NOTIFY_COMPLETED,
        &MhdCallbacks::completed, server.get(), MHD_OPTION_NOTIFY_CONNECTION, &MhdCallbacks::connection, server.get(),
        MHD_OPTION_EXTERNAL_LOGGER, &MhdCallbacks::log, server.get(), MHD_OPTION_DIGEST_AUTH_RANDOM,
        server->digestRandom_.size(), server->digestRandom_.data(), MHD_OPTION_NONCE_NC_SIZE, kDigestNonces,
        MHD_OPTION_UNESCAPE_CALLBACK, &MhdCallbacks::keepEscaped, nullptr,
        options.tls.empty() ? MHD_OPTION_END : MHD_OPTION_HTTPS_CERT_CALLBACK, TlsCertificate::callback(),
        MHD_OPTION_END);
    if (!server->daemon_)
        return makeError(ErrorCode::Io, "http: libmicrohttpd could not start on " + address->describe());
    [[maybe_unused]] const int owned = socket->release(); // libmicrohttpd closes it when it stops
    return server;
}

HttpServer::HttpServer(const HttpOptions &options, ListenAddress address, JpegFeed &feed, ApiHandler api,
                       Logger &logger)
    : options_(options), address_(std::move(address)), feed_(feed), api_(std::move(api)), logger_(logger),
      slots_(SlotLimits{options.maxPendingPerAddress, options.maxClients, std::chrono::seconds(kHeaderDeadlineSec),
                        std::chrono::seconds(kBodyDeadlineSec)})
{}

bool httpBuiltIn()
{
    return true;
}

HttpServer::~HttpServer()
{
    if (!daemon_)
        return;
    // Suspended connections must be resumed before the daemon stops (libmicrohttpd's rule); streams then end.
    stopping_ = true;
    resumeAll();
    MHD_run(daemon_);
    MHD_stop_daemon(daemon_);
}

int HttpServer::fd() const
{
    const MHD_DaemonInfo *info = MHD_get_daemon_info(daemon_, MHD_DAEMON_INFO_EPOLL_FD);
    return info ? info->epoll_fd : -1;
}

void HttpServer::run()
{
    // A connection still ready after one pass (a stream part larger than a block) is served again at once, up to a
    // bound, rather than a loop turn later.
    constexpr int kMaxPasses = 16;
    for (int pass = 0; pass < kMaxPasses; ++pass) {
        MHD_run(daemon_);
        MHD_UNSIGNED_LONG_LONG ms = 1;
        // A connection shut down by shed() ends on the next pass, which frees its slot for the next accept.
        const bool shedSome = std::exchange(shed_, false);
        const bool again = closeHungUp() || shedSome || (MHD_get_timeout(daemon_, &ms) == MHD_YES && ms == 0);
        if (!again)
            break;
    }
}

bool HttpServer::closeHungUp()
{
    // libmicrohttpd 0.9.75's epoll mode misses the end of a connection whose client sent part of a request and
    // closed at once (the FIN arrives with the data; the edge-triggered read never looks again), and would hold its
    // slot until the idle timeout: a few such clients a second would fill max_clients. Such a connection can never
    // complete its request; shutting it down here gives libmicrohttpd an event it does see.
    std::vector<pollfd> waiting;
    for (const Connection *open : connections_)
        if (!open->inRequest && open->fd >= 0)
            waiting.push_back({open->fd, POLLRDHUP, 0});
    if (waiting.empty() || ::poll(waiting.data(), waiting.size(), 0) <= 0)
        return false;
    bool closed = false;
    for (const pollfd &p : waiting)
        if (p.revents & (POLLRDHUP | POLLHUP | POLLERR)) {
            ::shutdown(p.fd, SHUT_RDWR);
            closed = true;
        }
    return closed;
}

Status HttpServer::replaceCertificate(const TlsFiles &files)
{
    auto certificate = TlsCertificate::create(files);
    if (!certificate)
        return certificate.error();
    TlsCertificate::serve(std::move(*certificate));
    options_.tls = files;
    return Ok{};
}

void HttpServer::shed(const std::vector<std::pair<RequestSlots::Id, ShedReason>> &victims)
{
    // Shut down, not closed: the fd stays libmicrohttpd's, which sees the end and closes the connection itself.
    for (const auto &[id, reason] : victims)
        for (const Connection *open : connections_)
            if (open->id() == id && open->fd >= 0) {
                ::shutdown(open->fd, SHUT_RDWR);
                shed_ = true;
            }
}

unsigned HttpServer::maxStreams() const
{
    if (options_.maxStreams)
        return options_.maxStreams;
    return options_.maxClients > kKeptForRequests ? options_.maxClients - kKeptForRequests : 1;
}

std::optional<std::chrono::milliseconds> HttpServer::timeout() const
{
    MHD_UNSIGNED_LONG_LONG ms = 0;
    if (MHD_get_timeout(daemon_, &ms) != MHD_YES)
        return std::nullopt;
    return std::chrono::milliseconds(ms);
}

void HttpServer::resumeAll()
{
    std::vector<MHD_Connection *> waiting;
    waiting.swap(suspended_);
    for (MHD_Connection *connection : waiting)
        MHD_resume_connection(connection);
}

void HttpServer::onJpeg()
{
    feed_.consumeWake();
    resumeAll();
    MHD_run(daemon_);
}

void HttpServer::onTick()
{
    const Clock::time_point now = Clock::now();
    for (StreamClient *stream : streams_) {
        const double seconds = std::chrono::duration<double>(now - stream->windowStart).count();
        if (seconds >= 1.0) {
            stream->fps = stream->windowParts / seconds;
            stream->windowParts = 0;
            stream->windowStart = now;
        }
    }
    shed(slots_.late(now));
    resumeAll(); // idle streams resend, and snapshot waits past their deadline answer
    MHD_run(daemon_);
}

HttpCounters HttpServer::counters() const
{
    HttpCounters out = counters_;
    out.streamClients = unsigned(streams_.size());
    for (const StreamClient *stream : streams_)
        out.streamFps.push_back(stream->fps);
    out.limits = {{"header_deadline", slots_.shedCount(ShedReason::HeaderDeadline)},
                  {"body_deadline", slots_.shedCount(ShedReason::BodyDeadline)},
                  {"max_pending_per_address", slots_.shedCount(ShedReason::PerAddress)},
                  {"max_clients", slots_.shedCount(ShedReason::Total)},
                  {"max_streams", streamsRefused_},
                  {"auth_refused", authFailures_.refused()},
                  {"auth_rate_limited", authFailures_.blockedCount()}};
    return out;
}

int HttpServer::answer(MHD_Connection *connection, const HttpResponse &response, DigestChallenge challenge)
{
    MHD_Response *r = MHD_create_response_from_buffer(response.body.size(), const_cast<char *>(response.body.data()),
                                                      MHD_RESPMEM_MUST_COPY);
    if (!r)
        return MHD_NO;
    MHD_add_response_header(r, MHD_HTTP_HEADER_CONTENT_TYPE, response.contentType.c_str());
    MHD_add_response_header(r, "X-Content-Type-Options", "nosniff");
    bool cacheSet = false;
    for (const auto &[name, value] : response.headers) {
        MHD_add_response_header(r, name.c_str(), value.c_str());
        cacheSet = cacheSet || name == MHD_HTTP_HEADER_CACHE_CONTROL;
    }
    if (!cacheSet)
        MHD_add_response_header(r, MHD_HTTP_HEADER_CACHE_CONTROL, "no-store");
    const MHD_Result queued =
        challenge == DigestChallenge::None
            ? MHD_queue_response(connection, response.status, r)
            : MHD_queue_auth_fail_response2(connection, kAuthRealm, kAuthRealm, r,
                                            challenge == DigestChallenge::Stale ? MHD_YES : MHD_NO,
                                            MHD_DIGEST_ALG_MD5); // what browsers and curl answer
    MHD_destroy_response(r);
    ++counters_.requests;
    if (response.status >= 400)
        ++counters_.refused;
    return queued;
}

Role HttpServer::digest(MHD_Connection *connection, bool &stale) const
{
    char *name = MHD_digest_auth_get_username(connection);
    if (name == nullptr)
        return Role::None;
    const BasicUser *user = credentials_.user(name);
    MHD_free(name);
    if (user == nullptr)
        return Role::None;
    const int checked = MHD_digest_auth_check2(connection, kAuthRealm, user->name.c_str(), user->password.c_str(),
                                               kDigestNonceSec, MHD_DIGEST_ALG_MD5);
    stale = checked == MHD_INVALID_NONCE;
    return checked == MHD_YES ? user->role : Role::None;
}

std::optional<HttpResponse> HttpServer::refuse(MHD_Connection *connection, const HttpRequest &request,
                                               DigestChallenge &challenge)
{
    const Role need = requiredRole(request.method, request.path);
    if (need == Role::Viewer && options_.viewerOpen)
        return std::nullopt;
    if (need == Role::Control && options_.control == ControlMode::Off)
        return HttpResponse::error(403, "control is off (http.control = \"off\")");
    if (need == Role::Control && options_.control == ControlMode::Open)
        return std::nullopt;
    const std::string authorization = header(connection, MHD_HTTP_HEADER_AUTHORIZATION);
    const auto now = AuthFailures::Clock::now();
    Role role = Role::None;
    if (!authorization.empty()) {
        if (authFailures_.blocked(request.peer, now))
            return HttpResponse::error(429, "too many refused credentials from this address: try again later");
        bool stale = false;
        role = authorization.starts_with("Digest ") && credentials_.hasUsers() ? digest(connection, stale)
                                                                               : credentials_.fromHeader(authorization);
        if (stale) // not a wrong credential: the client answers a fresh nonce without asking its user
            challenge = DigestChallenge::Stale;
        else if (role == Role::None)
            if (const std::string line = authFailures_.failed(
                    request.peer, request.method + (need == Role::Control ? ", a change" : ", watching"), now);
                !line.empty())
                logger_.warning(line); // the address and the request, never what was sent
    }
    if (role == Role::None) {
        HttpResponse refused = HttpResponse::error(
            401, need == Role::Control ? "control needs the token: Authorization: Bearer TOKEN (or a control user)"
                                       : "watching needs a credential: a viewer or control token or user");
        refused.headers.emplace_back(MHD_HTTP_HEADER_WWW_AUTHENTICATE, "Bearer");
        if (credentials_.hasUsers()) {
            refused.headers.emplace_back(MHD_HTTP_HEADER_WWW_AUTHENTICATE,
                                         std::string("Basic realm=\"") + kAuthRealm + "\", charset=\"UTF-8\"");
            if (challenge == DigestChallenge::None)
                challenge = DigestChallenge::Fresh;
        }
        return refused;
    }
    if (int(role) < int(need))
        return HttpResponse::error(403, "a viewer credential may watch, not change: this needs the control credential");
    return std::nullopt;
}

int HttpServer::access(MHD_Connection *connection, const std::string &rawUrl, const std::string &method,
                       Exchange &exchange)
{
    if (exchange.tooLarge)
        return answer(connection,
                      HttpResponse::error(413, "the body is over " + std::to_string(kMaxBodyBytes) + " bytes"));
    HttpRequest request;
    request.method = method;
    std::map<std::string, std::string> query; // as sent: keepEscaped left the %-escapes
    MHD_get_connection_values(connection, MHD_GET_ARGUMENT_KIND, &collectQuery, &query);
    size_t urlBytes = rawUrl.size();
    for (const auto &[key, value] : query)
        urlBytes += key.size() + value.size() + 2;
    if (urlBytes > kMaxUrlBytes)
        return answer(connection,
                      HttpResponse::error(414, "the URL is over " + std::to_string(kMaxUrlBytes) + " bytes"));
    auto path = percentDecoded(rawUrl);
    if (!path)
        return answer(connection, HttpResponse::error(400, "the path: " + path.error().message));
    request.path = std::move(*path);
    for (const auto &[key, value] : query) {
        auto decodedKey = percentDecoded(key), decodedValue = percentDecoded(value);
        if (!decodedKey || !decodedValue)
            return answer(connection,
                          HttpResponse::error(400, "the query's '" + key + "': " +
                                                       (decodedKey ? decodedValue : decodedKey).error().message));
        request.query[*decodedKey] = std::move(*decodedValue);
    }
    const std::string &url = request.path;
    const bool reading = method == "GET" || method == "HEAD";
    const bool hangUp = method == "DELETE" && url.starts_with("/whep/"); // WHEP's one DELETE
    if (!reading && method != "PUT" && method != "POST" && !hangUp)
        return answer(connection, HttpResponse::error(405, "method " + method + " is not served"));
    if (!reading && (url == "/stream" || url == "/snapshot")) // before the credential check: none makes it right
        return answer(connection, HttpResponse::error(405, "GET " + url));
    request.peer = peerOf(connection);
    DigestChallenge challenge = DigestChallenge::None;
    if (auto refused = refuse(connection, request, challenge))
        return answer(connection, *refused, challenge);
    if (reading && url == "/stream")
        return startStream(connection);
    if (reading && url == "/snapshot") {
        exchange.raw = request.query.count("raw") && request.query["raw"] != "0";
        return answerSnapshot(connection, exchange);
    }
    if (reading) {
        if (auto file = readPageFile(options_.pageDirectory, url)) {
            HttpResponse response;
            response.contentType = file->contentType;
            response.body = std::move(file->body);
            response.headers.emplace_back(MHD_HTTP_HEADER_CACHE_CONTROL, "no-cache");
            response.headers.emplace_back("Content-Security-Policy", "default-src 'self'; img-src 'self' blob:");
            return answer(connection, response);
        }
    }
    request.body = std::move(exchange.body);
    if (const char *type = MHD_lookup_connection_value(connection, MHD_HEADER_KIND, MHD_HTTP_HEADER_CONTENT_TYPE))
        request.contentType = type;
    return answer(connection, api_(request));
}

int HttpServer::answerSnapshot(MHD_Connection *connection, Exchange &exchange)
{
    const Clock::time_point now = Clock::now();
    if (!exchange.waiting) {
        // The next frame after the request (two publications: the one being encoded may predate it), so that a
        // snapshot after a control change shows the change.
        const auto latest = feed_.latest(exchange.raw);
        exchange.afterGeneration = (latest ? latest->generation : 0) + 1;
        exchange.deadline = now + kSnapshotWait;
        exchange.waiting = true;
        feed_.addSnapshotWaiter(exchange.raw, +1);
    }
    const auto latest = feed_.latest(exchange.raw);
    if (!latest || latest->generation <= exchange.afterGeneration) {
        if (now < exchange.deadline) {
            MHD_suspend_connection(connection);
            suspended_.push_back(connection);
            return MHD_YES;
        }
        exchange.waiting = false;
        feed_.addSnapshotWaiter(exchange.raw, -1);
        return answer(connection, HttpResponse::error(503, "no frame within 3 s: the source is not delivering"));
    }
    exchange.waiting = false;
    feed_.addSnapshotWaiter(exchange.raw, -1);
    HttpResponse response;
    response.contentType = "image/jpeg";
    response.body.assign(latest->bytes.begin(), latest->bytes.end());
    response.headers = {{"X-Timestamp-Us", std::to_string(latest->timestampUs)},
                        {"X-Sequence", std::to_string(latest->sequence)},
                        {MHD_HTTP_HEADER_PRAGMA, "no-cache"}};
    return answer(connection, response);
}

int HttpServer::startStream(MHD_Connection *connection)
{
    if (streams_.size() >= maxStreams()) {
        ++streamsRefused_;
        return answer(connection, HttpResponse::error(503, "too many /stream viewers (http.max_streams = " +
                                                               std::to_string(maxStreams()) + ")"));
    }
    auto *client = new StreamClient;
    client->server = this;
    client->connection = connection;
    client->nextDue = Clock::now();
    // The first part is a frame encoded after the client came: the feed may hold one from long ago (nobody watched,
    // so nothing was encoded since). Only a source that sends nothing for kIdleResend gets the old one.
    const auto latest = feed_.latest();
    client->lastGeneration = latest ? latest->generation : 0;
    client->lastSent = client->nextDue;
    MHD_Response *r = MHD_create_response_from_callback(MHD_SIZE_UNKNOWN, kStreamBlockBytes, &MhdCallbacks::readStream,
                                                        client, &MhdCallbacks::freeStream);
    if (!r) {
        delete client;
        return MHD_NO;
    }
    streams_.push_back(client);
    feed_.setWatchers(unsigned(streams_.size()));
    MHD_add_response_header(r, MHD_HTTP_HEADER_CONTENT_TYPE,
                            (std::string("multipart/x-mixed-replace;boundary=") + kBoundary).c_str());
    MHD_add_response_header(r, MHD_HTTP_HEADER_CACHE_CONTROL, "no-store");
    MHD_add_response_header(r, MHD_HTTP_HEADER_PRAGMA, "no-cache");
    MHD_add_response_header(r, "X-Content-Type-Options", "nosniff");
    const MHD_Result queued = MHD_queue_response(connection, MHD_HTTP_OK, r);
    MHD_destroy_response(r);
    ++counters_.requests;
    return queued;
}

ssize_t HttpServer::fillStream(StreamClient &client, char *buffer, size_t max)
{
    if (stopping_)
        return MHD_CONTENT_READER_END_WITH_ERROR;
    static const std::string kTrailer = std::string("\r\n--") + kBoundary + "\r\n";
    const size_t partBytes = client.frame ? client.partHeader.size() + client.frame->bytes.size() + kTrailer.size() : 0;
    if (client.offset >= partBytes) {
        // The newest frame, not the next one: a client that reads slowly skips frames instead of falling behind.
        const Clock::time_point now = Clock::now();
        const auto latest = feed_.latest();
        const bool fresh = latest && latest->generation != client.lastGeneration;
        const bool due = now + std::chrono::milliseconds(2) >= client.nextDue;
        const bool idle = latest && now - client.lastSent >= kIdleResend;
        if (!((fresh && due) || idle)) {
            MHD_suspend_connection(client.connection);
            suspended_.push_back(client.connection);
            return 0;
        }
        const auto interval =
            std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / options_.streamFps));
        client.nextDue = client.nextDue + interval < now ? now + interval : client.nextDue + interval;
        client.frame = latest;
        client.lastGeneration = latest->generation;
        client.lastSent = now;
        client.offset = 0;
        client.partHeader = (client.first ? std::string("--") + kBoundary + "\r\n" : std::string()) +
                            "Content-Type: image/jpeg\r\nContent-Length: " + std::to_string(latest->bytes.size()) +
                            "\r\nX-Timestamp-Us: " + std::to_string(latest->timestampUs) +
                            "\r\nX-Sequence: " + std::to_string(latest->sequence) + "\r\n\r\n";
        client.first = false;
        ++client.windowParts;
        ++counters_.partsSent;
    }
    // Copy from the three pieces of the part: its headers, the JPEG, the next boundary (sent at once, so that a
    // browser shows this part without waiting for the next one).
    const std::string_view pieces[] = {
        client.partHeader,
        std::string_view(reinterpret_cast<const char *>(client.frame->bytes.data()), client.frame->bytes.size()),
        kTrailer};
    size_t copied = 0, start = 0;
    for (const std::string_view piece : pieces) {
        if (copied < max && client.offset < start + piece.size()) {
            const size_t from = client.offset - start;
            const size_t n = std::min(max - copied, piece.size() - from);
            std::memcpy(buffer + copied, piece.data() + from, n);
            copied += n;
            client.offset += n;
        }
        start += piece.size();
    }
    return ssize_t(copied);
}

} // namespace overlayd
