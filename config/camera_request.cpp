// JSON request bodies become TOML tables, so that the config file's readers judge them and every message is one a
// config-file user would recognise.
#include "config/camera_request.h"

#include <nlohmann/json.hpp>

#include "config/config_sections.h"
#include "config/json_body.h"

namespace overlayd {

namespace {

bool toToml(const nlohmann::json &value, size_t depth, std::string &why, std::unique_ptr<toml::node> &out)
{
    if (depth > kMaxCameraRequestDepth) {
        why = "nested deeper than " + std::to_string(kMaxCameraRequestDepth) + " levels";
        return false;
    }
    if (value.is_object()) {
        auto table = std::make_unique<toml::table>();
        for (const auto &[key, item] : value.items()) {
            std::unique_ptr<toml::node> node;
            if (!toToml(item, depth + 1, why, node))
                return false;
            table->insert_or_assign(key, std::move(*node));
        }
        out = std::move(table);
    } else if (value.is_array()) {
        auto array = std::make_unique<toml::array>();
        for (const auto &item : value) {
            std::unique_ptr<toml::node> node;
            if (!toToml(item, depth + 1, why, node))
                return false;
            array->push_back(std::move(*node));
        }
        out = std::move(array);
    } else if (value.is_boolean()) {
        out = std::make_unique<toml::value<bool>>(value.get<bool>());
    } else if (value.is_number_integer()) {
        if (value.is_number_unsigned() && value.get<uint64_t>() > uint64_t(INT64_MAX)) {
            why = "a number out of range";
            return false;
        }
        out = std::make_unique<toml::value<int64_t>>(value.get<int64_t>());
    } else if (value.is_number_float()) {
        out = std::make_unique<toml::value<double>>(value.get<double>());
    } else if (value.is_string()) {
        out = std::make_unique<toml::value<std::string>>(value.get<std::string>());
    } else {
        why = "null is not a value";
        return false;
    }
    return true;
}

} // namespace

Result<CameraSpec> cameraFromJson(std::string_view json, const CameraSpec &live, unsigned width, unsigned height)
{
    auto parsed = parseJsonBody(json);
    if (!parsed)
        return parsed.error();
    const nlohmann::json &body = *parsed;
    if (!body.is_object() || body.empty())
        return makeError(ErrorCode::InvalidArgument, "the body must be a JSON object of [camera] keys");
    std::string why;
    std::unique_ptr<toml::node> converted;
    if (!toToml(body, 0, why, converted))
        return makeError(ErrorCode::InvalidArgument, "camera: " + why);
    const toml::table &table = *converted->as_table();

    Problems problems("request");
    TableReader camera(table, "camera", problems);
    CameraSpec spec = live;
    for (std::string_view refused : {"calibration", "frame"})
        if (camera.has(refused))
            camera.problem(refused, "not through the API: it names a file or frame of the config file");
    bool posed = false;
    for (std::string_view key : kPoseKeys)
        posed = posed || table.contains(key);
    if (posed)
        readPose(camera, spec.pose);
    CameraKeys keys;
    readIntrinsics(camera, ".", spec, keys);
    camera.finish();
    if (problems.empty()) {
        if (auto built = spec.build(width, height); !built)
            camera.problem(posed ? "pose" : keys.intrinsics, built.error().message);
    }
    if (problems.empty())
        return spec;
    std::string message;
    for (const ConfigProblem &problem : problems.sorted())
        message += (message.empty() ? "" : "; ") + problem.key + ": " + problem.message;
    return makeError(ErrorCode::InvalidArgument, message);
}

} // namespace overlayd
