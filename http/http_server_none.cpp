// SPDX-License-Identifier: Apache-2.0
// The HttpServer of an overlayd built without libmicrohttpd (OVERLAYD_HTTP=OFF): it never starts, saying why. The
// config refuses [http] first (httpBuiltIn), so only a caller that skipped the config meets this refusal.
#include "http/http_server.h"

namespace overlayd {

bool httpBuiltIn()
{
    return false;
}

Result<std::unique_ptr<HttpServer>> HttpServer::start(const HttpOptions &, JpegFeed &, ApiHandler, Logger &)
{
    return makeError(ErrorCode::Unsupported,
                     "this overlayd was built without the HTTP server (CMake option OVERLAYD_HTTP, libmicrohttpd)");
}

HttpServer::~HttpServer() = default;

Result<TlsFiles> readTlsFiles(const std::string &, const std::string &)
{
    return makeError(ErrorCode::Unsupported, "this overlayd was built without the HTTP server");
}

Status HttpServer::replaceCertificate(const TlsFiles &)
{
    return makeError(ErrorCode::Unsupported, "this overlayd was built without the HTTP server");
}

int HttpServer::fd() const
{
    return -1;
}

void HttpServer::run() {}

std::optional<std::chrono::milliseconds> HttpServer::timeout() const
{
    return std::nullopt;
}

void HttpServer::onJpeg() {}

void HttpServer::onTick() {}

HttpCounters HttpServer::counters() const
{
    return counters_;
}

} // namespace overlayd
