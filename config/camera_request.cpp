// JSON request bodies become TOML tables, so that the config file's readers judge them and every message is one a
// config-file user would recognise. The drop-in is plain TOML written here and read back by the loader.
#include "config/camera_request.h"

#include "base/number_text.h"
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

#include "config/config_sections.h"
#include "config/json_body.h"
#include "projection/pose.h"

namespace overlayd {

namespace {

constexpr std::string_view kPoseKeys[] = {"eye",         "target", "gaze", "up",    "prp",  "vpn",  "vup",  "position",
                                          "orientation", "axes",   "yaw",  "pitch", "roll", "rvec", "tvec", "rmat"};

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

std::string numberText(double value)
{
    return shortNumber(value, 17);
}

std::string vectorText(const glm::dvec3 &v)
{
    return "[" + numberText(v.x) + ", " + numberText(v.y) + ", " + numberText(v.z) + "]";
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

    config::Problems problems("request");
    config::TableReader camera(table, "camera", problems);
    CameraSpec spec = live;
    for (std::string_view refused : {"calibration", "frame"})
        if (camera.has(refused))
            camera.problem(refused, "not through the API: it names a file or frame of the config file");
    bool posed = false;
    for (std::string_view key : kPoseKeys)
        posed = posed || table.contains(key);
    if (posed)
        config::readPose(camera, spec.pose);
    config::CameraKeys keys;
    config::readIntrinsics(camera, ".", spec, keys);
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

std::string liveDropInPath(const std::string &configPath)
{
    std::filesystem::path path(configPath);
    const std::string stem = path.extension() == ".toml" ? path.stem().string() : path.filename().string();
    return (path.parent_path() / (stem + ".live.toml")).string();
}

Result<std::string> liveDropInText(const CameraSpec &camera, bool withIntrinsics)
{
    const Pose &pose = camera.pose;
    // world_from_opengl-axes: the transpose of the pose's rotation (x_camera = R x_mount + t).
    const glm::dquat orientation = glm::quat_cast(glm::transpose(pose.rotation));
    const YawPitchRoll ypr = yawPitchRollOf(pose);
    std::string text = "# Written by overlayd (POST /api/save): the live camera, read after the main config file.\n"
                       "# Delete this file to go back to the main file's pose.\n[camera]\n";
    text += "position = " + vectorText(pose.position()) + "\n";
    text += "orientation = [" + numberText(orientation.w) + ", " + numberText(orientation.x) + ", " +
            numberText(orientation.y) + ", " + numberText(orientation.z) + "]\naxes = \"opengl\"\n";
    text += "# yaw = " + numberText(ypr.yawDeg) + ", pitch = " + numberText(ypr.pitchDeg) +
            ", roll = " + numberText(ypr.rollDeg) + " (degrees)\n";
    if (!withIntrinsics)
        return text;
    if (camera.form == IntrinsicsForm::FieldOfView) {
        text += "fov = " + numberText(camera.fovDeg) + "\nfov_axis = \"" +
                (camera.fovAxis == FovAxis::Vertical ? "vertical" : "horizontal") + "\"\n";
    } else if (camera.form == IntrinsicsForm::Pinhole) {
        const PinholeIntrinsics &p = camera.pinhole;
        text += "pinhole = { fx = " + numberText(p.fx) + ", fy = " + numberText(p.fy) + ", cx = " + numberText(p.cx) +
                ", cy = " + numberText(p.cy) + ", skew = " + numberText(p.skew);
        if (p.width > 0)
            text += ", width = " + std::to_string(p.width) + ", height = " + std::to_string(p.height);
        text += " }\n";
    } else {
        return makeError(ErrorCode::Unsupported, "save writes fov or pinhole intrinsics; these are another form");
    }
    return text;
}

Result<std::string> writeLiveDropIn(const std::string &configPath, const CameraSpec &camera, bool withIntrinsics)
{
    auto text = liveDropInText(camera, withIntrinsics);
    if (!text)
        return text.error();
    const std::string path = liveDropInPath(configPath), temporary = path + ".tmp";
    {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        out << *text;
        out.flush();
        if (!out)
            return makeError(ErrorCode::Io, "cannot write " + temporary);
    }
    std::error_code error;
    std::filesystem::rename(temporary, path, error);
    if (error)
        return makeError(ErrorCode::Io, "cannot replace " + path + ": " + error.message());
    return path;
}

} // namespace overlayd
