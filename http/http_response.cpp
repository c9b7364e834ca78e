// SPDX-License-Identifier: Apache-2.0
// The answers the daemon's API builds: JSON bodies and JSON errors. Apart from the server, so that a build without
// libmicrohttpd (http_server_none.cpp) still has them.
#include "http/http_server.h"

#include "base/utf8.h"

namespace overlayd {

HttpResponse HttpResponse::json(unsigned status, std::string body)
{
    HttpResponse response;
    response.status = status;
    response.body = std::move(body);
    if (response.body.empty() || response.body.back() != '\n')
        response.body += '\n';
    return response;
}

HttpResponse HttpResponse::error(unsigned status, const std::string &message)
{
    // A message may quote what a client sent (a path, a parser's "last read"): quotable() makes it valid UTF-8.
    std::string escaped;
    for (const char c : quotable(message, kMaxErrorBytes)) {
        if (c == '"' || c == '\\')
            escaped += '\\';
        escaped += c;
    }
    return json(status, "{\"error\":\"" + escaped + "\"}");
}

} // namespace overlayd
