// SPDX-License-Identifier: Apache-2.0
// JSON request bodies become TOML tables, so that the config file's readers judge them and every message is one a
// config-file user would recognise.
#include "config/camera_request.h"

#include <algorithm>
#include <iterator>
#include <nlohmann/json.hpp>

#include "config/config_sections.h"
#include "config/json_body.h"
#include "projection/pose.h"

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

// A request that names only some of position, yaw, pitch and roll (and no key of another pose form) changes only
// those: the others are the live pose's. {"yaw": 100} turns the camera where it stands.
void completeYawPitchRoll(nlohmann::json &body, const Pose &live)
{
    constexpr std::string_view kYawPitchRoll[] = {"position", "yaw", "pitch", "roll"};
    size_t named = 0;
    for (std::string_view key : kPoseKeys) {
        const bool inForm =
            std::find(std::begin(kYawPitchRoll), std::end(kYawPitchRoll), key) != std::end(kYawPitchRoll);
        if (body.contains(key)) {
            if (!inForm)
                return;
            ++named;
        }
    }
    if (named == 0 || named == std::size(kYawPitchRoll))
        return;
    const YawPitchRoll ypr = yawPitchRollOf(live);
    if (!body.contains("position"))
        body["position"] = {ypr.position.x, ypr.position.y, ypr.position.z};
    for (const auto &[key, value] : {std::pair{"yaw", ypr.yawDeg}, {"pitch", ypr.pitchDeg}, {"roll", ypr.rollDeg}})
        if (!body.contains(key))
            body[key] = value;
}

} // namespace

Result<CameraSpec> cameraFromJson(std::string_view json, const CameraSpec &live, unsigned width, unsigned height)
{
    auto parsed = parseJsonBody(json);
    if (!parsed)
        return parsed.error();
    nlohmann::json &body = *parsed;
    if (!body.is_object() || body.empty())
        return makeError(ErrorCode::InvalidArgument, "the body must be a JSON object of [camera] keys");
    completeYawPitchRoll(body, live.pose);
    std::string why;
    std::unique_ptr<toml::node> converted;
    if (!toToml(body, 0, why, converted))
        return makeError(ErrorCode::InvalidArgument, "camera: " + why);
    const toml::table &table = *converted->as_table();

    // Refused before any key is read: reading `calibration` opens its file, and the answer would tell a missing
    // file from an unreadable one, a map of the machine's files for whoever holds the token.
    for (std::string_view refused : {"calibration", "frame"})
        if (table.contains(refused))
            return makeError(ErrorCode::InvalidArgument, "camera." + std::string(refused) +
                                                             ": not through the API: it names a file or frame of "
                                                             "the config file");
    Problems problems("request");
    TableReader camera(table, "camera", problems);
    CameraSpec spec = live;
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
