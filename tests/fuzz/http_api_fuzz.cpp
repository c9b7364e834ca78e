// SPDX-License-Identifier: Apache-2.0
// libFuzzer target: any request through the HTTP API's handlers (HttpApi::handle: /state, /metrics, PUT
// /api/camera|layers|text, /api/project, /api/unproject, /api/save), on a daemon started once with a small scene.
// The input is "METHOD PATH?QUERY\nBODY", as libmicrohttpd hands the parts over after its own parsing.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "fuzz_daemon.h"

namespace {

constexpr std::string_view kConfig = R"(
[source]
kind = "synthetic"
format = "YUYV"
width = 160
height = 120
fps = 30.0
[camera]
position = [0.0, -6.0, 3.0]
yaw = 90.0
pitch = 25.0
fov = 60.0
[[annotation]]
type = "axes"
length = 1.0
style = { layer = "axes" }
[[annotation]]
type = "grid"
spacing = 1.0
extent = 5.0
style = { layer = "grid" }
[[annotation]]
type = "text"
text = "{slot:status} {frame}"
position = [4.0, 4.0]
[[sink]]
kind = "null"
)";

overlayd::HttpRequest request(std::string_view input)
{
    overlayd::HttpRequest request;
    const size_t lineEnd = std::min(input.find('\n'), input.size());
    const std::string_view line = input.substr(0, lineEnd);
    request.body = std::string(input.substr(std::min(lineEnd + 1, input.size())));
    const size_t space = line.find(' ');
    request.method = std::string(line.substr(0, std::min(space, line.size())));
    std::string_view target = space == std::string_view::npos ? std::string_view() : line.substr(space + 1);
    const size_t question = target.find('?');
    request.path = std::string(target.substr(0, question));
    if (question != std::string_view::npos) {
        std::string_view query = target.substr(question + 1);
        while (!query.empty()) {
            const size_t amp = std::min(query.find('&'), query.size());
            const std::string_view pair = query.substr(0, amp);
            const size_t equals = std::min(pair.find('='), pair.size());
            request.query[std::string(pair.substr(0, equals))] =
                std::string(pair.substr(std::min(equals + 1, pair.size())));
            query.remove_prefix(std::min(amp + 1, query.size()));
        }
    }
    request.peer = "127.0.0.1";
    return request;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static FuzzDaemon running("http_api_fuzz", kConfig);
    (void)running.api->handle(request(std::string_view(reinterpret_cast<const char *>(data), size)));
    return 0;
}
