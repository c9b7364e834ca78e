// SPDX-License-Identifier: Apache-2.0
// The HTTP API's answers. JSON goes out through nlohmann::json; JSON coming in is read by config/ (camera changes)
// or here (a layer's visibility, a slot's text, pixels), each with the limits the config file has.
#include "control/http_api.h"

#include <charconv>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "alignment/point_queries.h"
#include "base/number_range.h"
#include "base/number_text.h"
#include "base/version.h"
#include "config/camera_request.h"
#include "config/json_body.h"
#include "config/live_drop_in.h"
#include "control/status_report.h"
#include "control/whep_api.h"
#include "drivers/source_kind_names.h"
#include "overlay/shapes/scene_checks.h"
#include "projection/pose.h"

namespace overlayd {

namespace {
using nlohmann::json;

constexpr size_t kMaxApiPoints = 4096; // /api/project and /api/unproject, per request

const char *stateName(DaemonStatus::State state)
{
    switch (state) {
    case DaemonStatus::State::Idle:
        return "idle";
    case DaemonStatus::State::Streaming:
        return "streaming";
    case DaemonStatus::State::Waiting:
        return "waiting";
    case DaemonStatus::State::Finished:
        return "finished";
    }
    return "?";
}

// What the numbers a person reads are rounded to: a micrometre, a millionth of a degree or of a pixel, a
// millisecond; well below what a camera or a click can tell, well above the arithmetic's noise (-6.000000000000003).
constexpr int kShownDecimals = 6;
constexpr int kShownSecondsDecimals = 3;
constexpr int kShownQuaternionDecimals = 7; // about 1e-5 degree

double shown(double value)
{
    return roundedTo(value, kShownDecimals);
}

json vec3(const glm::dvec3 &v)
{
    return json::array({shown(v.x), shown(v.y), shown(v.z)});
}

// The intrinsics key the camera was given by, so that the page edits that one (a field of view stays one).
const char *intrinsicsFormName(IntrinsicsForm form)
{
    switch (form) {
    case IntrinsicsForm::FieldOfView:
        return "fov";
    case IntrinsicsForm::Frustum:
        return "frustum";
    case IntrinsicsForm::Pinhole:
        return "pinhole";
    case IntrinsicsForm::Window:
        return "window";
    case IntrinsicsForm::Orthographic:
    case IntrinsicsForm::WindowOrthographic:
        break;
    }
    return "orthographic";
}

json cameraJson(const CameraSpec &spec, const Result<Camera> &camera)
{
    const YawPitchRoll ypr = yawPitchRollOf(spec.pose);
    const glm::dquat orientation = glm::quat_cast(glm::transpose(spec.pose.rotation));
    json out = {{"frame", spec.mountFrame},
                {"origin", spec.viewport.origin == Origin::TopLeft ? "top-left" : "bottom-left"},
                {"position", vec3(ypr.position)},
                {"yaw", shown(ypr.yawDeg)},
                {"pitch", shown(ypr.pitchDeg)},
                {"roll", shown(ypr.rollDeg)},
                {"pose",
                 {{"position", vec3(ypr.position)},
                  {"orientation", json::array({roundedTo(orientation.w, kShownQuaternionDecimals),
                                               roundedTo(orientation.x, kShownQuaternionDecimals),
                                               roundedTo(orientation.y, kShownQuaternionDecimals),
                                               roundedTo(orientation.z, kShownQuaternionDecimals)})},
                  {"axes", "opengl"}}}};
    if (camera) {
        // The pinhole the stream is drawn with (any intrinsics form, scaled to the stream's frame), in
        // [camera.pinhole]'s convention: pixel centres at integers, so pasting these values draws the same overlay.
        // The inverse of Projection::pinhole's matrix.
        const glm::dmat4 &p = camera->projection().matrix();
        const Viewport &viewport = camera->viewport();
        const double width = viewport.window().width, height = viewport.window().height;
        const double fx = p[0][0] * width / 2.0, fy = p[1][1] * height / 2.0;
        out["intrinsics"] = {{"fx", shown(fx)},
                             {"fy", shown(fy)},
                             {"cx", shown((1.0 - p[2][0]) * width / 2.0 - 0.5)},
                             {"cy", shown((1.0 + p[2][1]) * height / 2.0 - 0.5)},
                             {"skew", shown(-p[1][0] * width / 2.0)},
                             {"width", width},
                             {"height", height},
                             {"hfov", shown(glm::degrees(2.0 * std::atan(width / (2.0 * fx))))},
                             {"vfov", shown(glm::degrees(2.0 * std::atan(height / (2.0 * fy))))},
                             {"form", intrinsicsFormName(spec.form)}};
        if (spec.form == IntrinsicsForm::FieldOfView) {
            out["intrinsics"]["fov"] = shown(spec.fovDeg);
            out["intrinsics"]["fov_axis"] = spec.fovAxis == FovAxis::Vertical ? "vertical" : "horizontal";
        }
    }
    return out;
}

// Numbers separated by ',' ';' or spaces: "x,y,z;x,y,z".
std::optional<std::vector<double>> numberList(const std::string &text)
{
    std::vector<double> out;
    const char *p = text.data(), *end = p + text.size();
    while (p < end) {
        if (*p == ',' || *p == ';' || *p == ' ') {
            ++p;
            continue;
        }
        double value = 0.0;
        const auto [next, error] = std::from_chars(p, end, value);
        if (error != std::errc() || !std::isfinite(value))
            return std::nullopt;
        out.push_back(value);
        p = next;
    }
    return out;
}

} // namespace

HttpApi::HttpApi(SceneControl &scene, const DaemonStatus &status, std::function<HttpCounters()> counters)
    : scene_(scene), status_(status), counters_(std::move(counters))
{}

HttpResponse HttpApi::handle(const HttpRequest &request)
{
    const std::string &path = request.path;
    const bool get = request.method == "GET" || request.method == "HEAD";
    constexpr std::string_view kLayers = "/api/layers/", kText = "/api/text/";
    if (path == "/state")
        return get ? state() : HttpResponse::error(405, "GET /state");
    if (path == "/metrics")
        return get ? metrics() : HttpResponse::error(405, "GET /metrics");
    if (path == "/api/camera")
        return request.method == "PUT" ? putCamera(request) : HttpResponse::error(405, "PUT /api/camera");
    if (path.rfind(kLayers, 0) == 0)
        return request.method == "PUT" ? putLayer(path.substr(kLayers.size()), request)
                                       : HttpResponse::error(405, "PUT /api/layers/NAME");
    if (path.rfind(kText, 0) == 0)
        return request.method == "PUT" ? putText(path.substr(kText.size()), request)
                                       : HttpResponse::error(405, "PUT /api/text/SLOT");
    if (path == "/api/project")
        return get ? project(request) : HttpResponse::error(405, "GET /api/project?points=x,y,z;...");
    if (path == "/api/unproject")
        return request.method == "POST" ? unproject(request) : HttpResponse::error(405, "POST /api/unproject");
    if (path == "/api/save")
        return request.method == "POST" ? save() : HttpResponse::error(405, "POST /api/save");
    if (isWhepPath(path))
        return handleWhep(status_, request);
    return HttpResponse::error(404, "no such path: " + path);
}

double HttpApi::measuredFps()
{
    const auto now = std::chrono::steady_clock::now();
    const double seconds = std::chrono::duration<double>(now - sampleTime_).count();
    const uint64_t frames = status_.framesIn();
    if (seconds >= 1.0) {
        fps_ = double(frames - sampleFrames_) / seconds;
        sampleTime_ = now;
        sampleFrames_ = frames;
    }
    return fps_;
}

HttpResponse HttpApi::state()
{
    const DaemonConfig &config = status_.config();
    const StreamFormat &format = status_.streamFormat();
    SceneControl &scene = scene_;
    json source = {{"kind", std::string(sourceKindName(config.source.kind))},
                   {"state", stateName(status_.state())},
                   {"frames", status_.framesIn()},
                   {"fps_measured", roundedTo(measuredFps(), kShownSecondsDecimals)}};
    if (config.source.kind == SourceKind::V4l2)
        source["device"] = config.source.v4l2.device;
    if (format.format)
        source.update({{"format", std::string(format.format->name)},
                       {"width", format.width},
                       {"height", format.height},
                       {"fps", format.fps}});
    json layers = json::array();
    for (const std::string &layer : scene.layerNames())
        layers.push_back({{"name", layer}, {"visible", scene.layerVisible(layer)}});
    json masks = json::array();
    for (const Annotation &annotation : scene.scene().annotations)
        if (const auto *mask = std::get_if<MaskShape>(&annotation.shape))
            masks.push_back({{"name", annotation.name},
                             {"layer", annotation.style.layer},
                             {"on", mask->world ? "world" : "screen"},
                             {"fill", mask->fill ? "colour" : "pixelate"}});
    json slots = json::object();
    for (const std::string &slot : textSlotNames(scene.scene()))
        slots[slot] = scene.slotText(slot);
    const HttpCounters http = counters_();
    const unsigned width = format.format ? format.width : config.source.width;
    const unsigned height = format.format ? format.height : config.source.height;
    json out = {
        {"version", overlaydVersion()},
        {"uptime_s", roundedTo(std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count(),
                               kShownSecondsDecimals)},
        {"source", source},
        {"camera", cameraJson(scene.camera(), scene.cameraFor(width, height))},
        {"layers", layers},
        {"masks", masks},
        {"text_slots", slots},
        {"sinks", json::array()},
        {"http",
         {{"connections", http.connections},
          {"stream_clients", http.streamClients},
          {"stream_fps", http.streamFps},
          {"parts_sent", http.partsSent},
          {"requests", http.requests}}}};
    // The config's pose (with its saved drop-in), for the page's "revert to the config".
    const YawPitchRoll configured = yawPitchRollOf(config.camera.pose);
    out["camera"]["configured"] = {{"position", vec3(configured.position)},
                                   {"yaw", shown(configured.yawDeg)},
                                   {"pitch", shown(configured.pitchDeg)},
                                   {"roll", shown(configured.rollDeg)}};
    StatusReport parts(std::chrono::steady_clock::now());
    addParts(parts);
    parts.writeState(out);
    return HttpResponse::json(200, writeJson(out));
}

HttpResponse HttpApi::metrics()
{
    const HttpCounters http = counters_();
    const auto now = std::chrono::steady_clock::now();
    StatusReport report(now);
    report.metric("overlayd_uptime_seconds", "gauge", "Seconds since the daemon started.",
                  std::chrono::duration<double>(now - started_).count());
    report.metric("overlayd_source_frames_total", "counter", "Frames the source delivered.",
                  double(status_.framesIn()));
    report.metric("overlayd_source_fps", "gauge", "Source frames per second, measured.", measuredFps());
    report.metric("overlayd_source_streaming", "gauge", "1 while the source streams, 0 while it is waited for.",
                  status_.state() == DaemonStatus::State::Streaming ? 1.0 : 0.0);
    addParts(report);
    report.metric("overlayd_http_connections", "gauge", "Open HTTP connections.", http.connections);
    report.metric("overlayd_http_stream_clients", "gauge", "Clients of /stream.", http.streamClients);
    report.metric("overlayd_http_parts_sent_total", "counter", "JPEG parts sent to /stream clients.",
                  double(http.partsSent));
    report.metric("overlayd_http_requests_total", "counter", "HTTP requests answered.", double(http.requests));
    report.metric("overlayd_http_refused_total", "counter", "HTTP requests answered with an error.",
                  double(http.refused));
    for (const auto &[limit, hits] : http.limits)
        report.metric("overlayd_http_limit_total", "counter",
                      "Connections a limit closed or refused (docs/config.md Limits).", double(hits),
                      StatusReport::label("limit", limit));
    HttpResponse response = HttpResponse::json(200, report.metricsText());
    response.contentType = "text/plain; version=0.0.4; charset=utf-8";
    return response;
}

void HttpApi::addParts(StatusReport &report) const
{
    for (const StatusReporter *reporter : status_.reporters())
        reporter->report(report);
}
HttpResponse HttpApi::putCamera(const HttpRequest &request)
{
    SceneControl &scene = scene_;
    const StreamFormat &format = status_.streamFormat();
    const unsigned width = format.format ? format.width : status_.config().source.width;
    const unsigned height = format.format ? format.height : status_.config().source.height;
    auto spec = cameraFromJson(request.body, scene.camera(), width, height);
    if (!spec)
        return HttpResponse::error(400, spec.error().message);
    if (auto applied = scene.apply(CameraChange{*spec}); !applied)
        return HttpResponse::error(400, "camera: " + applied.error().message);
    return HttpResponse::json(200, writeJson(cameraJson(scene.camera(), scene.cameraFor(width, height))));
}

HttpResponse HttpApi::putLayer(const std::string &layer, const HttpRequest &request)
{
    SceneControl &scene = scene_;
    const auto names = scene.layerNames();
    if (std::find(names.begin(), names.end(), layer) == names.end()) {
        std::string known;
        for (const std::string &name : names)
            known += (known.empty() ? "" : ", ") + name;
        return HttpResponse::error(404, "no layer '" + layer +
                                            "' in the scene; its layers: " + (known.empty() ? "none" : known));
    }
    const auto body = parseJsonBody(request.body);
    if (!body)
        return HttpResponse::error(400, body.error().message);
    if (!body->is_object() || !body->contains("visible") || !(*body)["visible"].is_boolean() || body->size() != 1)
        return HttpResponse::error(400, "visible: expected {\"visible\": true|false}");
    const bool visible = (*body)["visible"].get<bool>();
    if (auto applied = scene.apply(LayerChange{layer, visible}); !applied)
        return HttpResponse::error(400, applied.error().message);
    return HttpResponse::json(200, writeJson(json({{"name", layer}, {"visible", visible}})));
}

HttpResponse HttpApi::putText(const std::string &slot, const HttpRequest &request)
{
    const auto slots = textSlotNames(scene_.scene());
    if (std::find(slots.begin(), slots.end(), slot) == slots.end())
        return HttpResponse::error(404, "no text in the scene shows the slot '" + slot + "' ({slot:" + slot + "})");
    const auto body = parseJsonBody(request.body);
    if (!body)
        return HttpResponse::error(400, body.error().message);
    if (!body->is_object() || !body->contains("text") || !(*body)["text"].is_string() || body->size() != 1)
        return HttpResponse::error(400, "text: expected {\"text\": \"...\"}");
    const std::string text = (*body)["text"].get<std::string>();
    if (auto applied = scene_.apply(TextChange{slot, text}); !applied)
        return HttpResponse::error(400, "text: " + applied.error().message);
    return HttpResponse::json(200, writeJson(json({{"slot", slot}, {"text", text}})));
}

HttpResponse HttpApi::project(const HttpRequest &request)
{
    const auto it = request.query.find("points");
    const auto numbers = it == request.query.end() ? std::nullopt : numberList(it->second);
    if (!numbers || numbers->empty() || numbers->size() % 3 != 0 || numbers->size() / 3 > kMaxApiPoints)
        return HttpResponse::error(400, "points: expected x,y,z;x,y,z;... (at most " + std::to_string(kMaxApiPoints) +
                                            " finite points)");
    if (const std::string why = numbersRefusal(*numbers, {"x", "y", "z"}, "point", kAnyMagnitude); !why.empty())
        return HttpResponse::error(400, "points: " + why);
    const StreamFormat &format = status_.streamFormat();
    auto camera = scene_.cameraFor(format.width, format.height);
    if (!format.format || !camera)
        return HttpResponse::error(503, "no stream yet: the camera is built for the stream's frame size");
    std::vector<glm::dvec3> world;
    for (size_t i = 0; i < numbers->size(); i += 3)
        world.emplace_back((*numbers)[i], (*numbers)[i + 1], (*numbers)[i + 2]);
    return HttpResponse::json(200, projectJson(*camera, world));
}

HttpResponse HttpApi::unproject(const HttpRequest &request)
{
    const auto body = parseJsonBody(request.body);
    if (!body)
        return HttpResponse::error(400, body.error().message);
    const json *pixels = body->is_object() && body->contains("pixels") ? &(*body)["pixels"] : nullptr;
    if (!pixels || !pixels->is_array() || pixels->empty() || pixels->size() > kMaxApiPoints)
        return HttpResponse::error(400, "pixels: expected {\"pixels\": [[u, v], ...]} with 1 to " +
                                            std::to_string(kMaxApiPoints) + " pixels");
    std::vector<double> numbers;
    for (const json &pixel : *pixels) {
        if (!pixel.is_array() || pixel.size() != 2 || !pixel[0].is_number() || !pixel[1].is_number())
            return HttpResponse::error(400, "pixels: each pixel is [u, v], two numbers");
        numbers.insert(numbers.end(), {pixel[0].get<double>(), pixel[1].get<double>()});
    }
    if (const std::string why = numbersRefusal(numbers, {"u", "v"}, "pixel", kAnyMagnitude); !why.empty())
        return HttpResponse::error(400, "pixels: " + why);
    std::vector<glm::dvec2> uv;
    for (size_t i = 0; i < numbers.size(); i += 2)
        uv.emplace_back(numbers[i], numbers[i + 1]);
    const StreamFormat &format = status_.streamFormat();
    auto camera = scene_.cameraFor(format.width, format.height);
    if (!format.format || !camera)
        return HttpResponse::error(503, "no stream yet: the camera is built for the stream's frame size");
    return HttpResponse::json(200, unprojectJson(*camera, Plane{}, uv));
}

HttpResponse HttpApi::save()
{
    // The whole live camera, merged into what the drop-in holds: a save after a restart keeps what an earlier save
    // wrote, and the saved config projects as the live camera does.
    auto written = writeLiveDropIn(status_.config().path, scene_.camera(), "POST /api/save");
    if (!written)
        return HttpResponse::error(500, written.error().message);
    return HttpResponse::json(200, writeJson(json({{"saved", *written}})));
}

} // namespace overlayd
