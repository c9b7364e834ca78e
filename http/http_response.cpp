// The answers the daemon's API builds: JSON bodies and JSON errors. Apart from the server, so that a build without
// libmicrohttpd (http_server_none.cpp) still has them.
#include "http/http_server.h"

namespace overlayd::http {

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
    std::string escaped;
    for (const char c : message) {
        if (c == '"' || c == '\\')
            escaped += '\\';
        if (static_cast<unsigned char>(c) < 0x20)
            escaped += ' ';
        else
            escaped += c;
    }
    return json(status, "{\"error\":\"" + escaped + "\"}");
}

} // namespace overlayd::http
