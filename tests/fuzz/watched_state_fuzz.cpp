// SPDX-License-Identifier: Apache-2.0
// libFuzzer target: any bytes in a watched [[input.text]] file and a watched [[input.path]] file, read by the inputs
// as the event loop would on a change, then GET /state through HttpApi::handle: the answer must be 200 and JSON
// that nlohmann's strict parser (which refuses invalid UTF-8) reads back. The daemon is started once with a scene
// that has a text slot and a polyline fed by the two files.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string_view>

#include <nlohmann/json.hpp>

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
type = "text"
text = "{slot:status}"
position = [4.0, 4.0]
[[annotation]]
name = "route"
type = "polyline"
points = [[0.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
[[input.text]]
slot = "status"
file = "status.txt"
[[input.path]]
annotation = "route"
file = "route.txt"
[[sink]]
kind = "null"
)";

// The fuzz input as a whole file: what a writer leaves once it closes the file or renames it in.
void write(const std::filesystem::path &file, std::string_view content)
{
    std::ofstream(file, std::ios::binary | std::ios::trunc).write(content.data(), std::streamsize(content.size()));
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static FuzzDaemon running("watched_state_fuzz", kConfig);
    const std::string_view input(reinterpret_cast<const char *>(data), size);
    write(running.folder / "status.txt", input);
    write(running.folder / "route.txt", input);
    running.daemon->textInputs().showAll();
    running.daemon->pathInputs().showAll();
    overlayd::HttpRequest request;
    request.method = "GET";
    request.path = "/state";
    const overlayd::HttpResponse state = running.api->handle(request);
    if (state.status != 200)
        std::abort();
    // Throws (and so fails the run) on anything that is not JSON, invalid UTF-8 in a string included.
    (void)nlohmann::json::parse(state.body);
    return 0;
}
