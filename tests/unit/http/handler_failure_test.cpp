// SPDX-License-Identifier: Apache-2.0
// An exception thrown by the API handler does not unwind through libmicrohttpd (which would end the process): the
// request is answered 500 with a JSON body, the failure is logged, and the server answers the next request.
#include "http/http_server.h"

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <poll.h>
#include <stdexcept>
#include <sys/socket.h>
#include <sys/un.h>
#include <thread>
#include <unistd.h>

#include <gtest/gtest.h>

using namespace overlayd;

namespace {

// The whole answer to one HTTP/1.0 request over the unix socket ("" when the connection failed).
std::string exchange(const std::string &socketPath, const std::string &request)
{
    const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    socketPath.copy(address.sun_path, sizeof(address.sun_path) - 1);
    std::string answer;
    if (::connect(fd, reinterpret_cast<const sockaddr *>(&address), sizeof(address)) == 0 &&
        ::write(fd, request.data(), request.size()) == ssize_t(request.size())) {
        char buffer[4096];
        for (ssize_t got; (got = ::read(fd, buffer, sizeof(buffer))) > 0;)
            answer.append(buffer, size_t(got));
    }
    ::close(fd);
    return answer;
}

struct Served {
    std::filesystem::path folder =
        std::filesystem::temp_directory_path() / ("overlayd-http-" + std::to_string(getpid()));
    std::vector<std::string> logged;
    Logger logger{[this](std::string_view line) { logged.emplace_back(line); }, false};
    std::unique_ptr<JpegFeed> feed;
    std::unique_ptr<HttpServer> server;

    Served()
    {
        std::filesystem::create_directories(folder);
        feed = std::move(*JpegFeed::create());
        HttpOptions options;
        options.enabled = true;
        options.listen = "unix:" + (folder / "http.sock").string();
        options.control = ControlMode::Open;
        auto started = HttpServer::start(
            options, *feed,
            [](const HttpRequest &request) -> HttpResponse {
                if (request.path == "/std")
                    throw std::runtime_error("a handler's bug");
                if (request.path == "/other")
                    throw 42;
                return HttpResponse::json(200, "{\"ok\":true}");
            },
            logger);
        if (started)
            server = std::move(*started);
    }
    ~Served() { std::filesystem::remove_all(folder); }

    // The answer to `request`, with the server pumped on this thread while a client thread asks.
    std::string ask(const std::string &request)
    {
        std::string answer;
        std::atomic<bool> done = false;
        std::thread client([&] {
            answer = exchange((folder / "http.sock").string(), request);
            done = true;
        });
        for (int i = 0; i < 500 && !done; ++i) {
            pollfd p{server->fd(), POLLIN, 0};
            ::poll(&p, 1, 10);
            server->run();
        }
        client.join();
        return answer;
    }
};

// The status code of an answer's first line ("HTTP/1.1 500 Internal Server Error"), 0 for no answer.
int statusOf(const std::string &answer)
{
    const size_t space = answer.find(' ');
    return space == std::string::npos ? 0 : std::atoi(answer.c_str() + space + 1);
}

} // namespace

TEST(HttpHandlerFailure, AnExceptionIsA500WithAJsonBodyAndTheServerGoesOn)
{
    Served served;
    ASSERT_NE(served.server, nullptr);
    const std::string failed = served.ask("GET /std HTTP/1.0\r\n\r\n");
    EXPECT_EQ(statusOf(failed), 500) << failed;
    EXPECT_NE(failed.find("\r\n\r\n{\"error\":\"internal error: a handler's bug\"}\n"), std::string::npos) << failed;

    const std::string other = served.ask("GET /other HTTP/1.0\r\n\r\n");
    EXPECT_EQ(statusOf(other), 500) << other;
    EXPECT_NE(other.find("{\"error\":\"internal error: "), std::string::npos) << other;

    const std::string fine = served.ask("GET /fine HTTP/1.0\r\n\r\n");
    EXPECT_EQ(statusOf(fine), 200) << fine;
    EXPECT_NE(fine.find("{\"ok\":true}"), std::string::npos) << fine;

    size_t errors = 0;
    for (const std::string &line : served.logged)
        errors += line.find("a request failed (answered 500)") != std::string::npos;
    EXPECT_EQ(errors, 2u);
}
