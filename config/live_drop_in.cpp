// SPDX-License-Identifier: Apache-2.0
// The drop-in is parsed with toml++, its [camera] merged with the live camera's keys and re-emitted by a small
// emitter whose floating-point numbers are std::to_chars' shortest exact form (every double reads back bit for bit).
#include "config/live_drop_in.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "base/number_text.h"
#include "base/regular_file.h"
#include "base/replace_file.h"
#include "config/config_sections.h"
#include "config/daemon_config.h"
#include "config/nesting_depth.h"

namespace overlayd {

namespace {

// The header's pose, for a person to read: 0.1 um and 1e-7 degree (the keys below keep every bit).
constexpr int kCommentDecimals = 7;
// A pose key is written as its 12-decimal rounding when that is within 1e-13 of it (relative above 1): far below
// what a pixel can show (1e-13 degree is 1e-12 px at 1000 px of focal length), far above atan2's rounding noise.
constexpr int kTidyDecimals = 12;
constexpr double kTidySlack = 1e-13;

std::string numberText(double value)
{
    char text[64];
    const auto [end, error] = std::to_chars(text, text + sizeof(text), value);
    std::string out(text, error == std::errc() ? end : text);
    // "2" would read back as an integer; "inf" and "nan" are TOML floats already.
    if (out.find_first_of(".en") == std::string::npos)
        out += ".0";
    return out;
}

bool isBareKey(std::string_view key)
{
    for (char c : key)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-')
            return false;
    return !key.empty();
}

std::string tomlText(const toml::node &node);

std::string keyText(std::string_view key)
{
    return isBareKey(key) ? std::string(key) : tomlText(toml::value<std::string>(std::string(key)));
}

// One line per value: tables inline, so that a kept table of any depth stays valid wherever it is written.
std::string tomlText(const toml::node &node)
{
    if (const toml::table *table = node.as_table()) {
        std::string out;
        for (const auto &[key, value] : *table)
            out += (out.empty() ? "{ " : ", ") + keyText(key.str()) + " = " + tomlText(value);
        return out.empty() ? "{}" : out + " }";
    }
    if (const toml::array *array = node.as_array()) {
        std::string out;
        for (const toml::node &item : *array)
            out += (out.empty() ? "" : ", ") + tomlText(item);
        return "[" + out + "]";
    }
    if (const auto *number = node.as_floating_point())
        return numberText(number->get());
    // Strings (one-line basic strings, escaped, valid as keys too), integers, booleans, dates: toml++'s own form.
    std::ostringstream out;
    out << toml::toml_formatter{node, toml::format_flags::none};
    return out.str();
}

toml::array numbers(std::initializer_list<double> values)
{
    toml::array out;
    for (double value : values)
        out.push_back(value);
    return out;
}

toml::array vectorArray(const glm::dvec3 &v)
{
    return numbers({v.x, v.y, v.z});
}

toml::table boundsTable(const FrustumBounds &b)
{
    return toml::table{{"left", b.left}, {"right", b.right}, {"bottom", b.bottom}, {"top", b.top}};
}

const char *distortionModelName(DistortionModel model)
{
    switch (model) {
    case DistortionModel::None:
        break;
    case DistortionModel::RadialTangential:
        return "plumb_bob";
    case DistortionModel::Rational:
        return "rational_polynomial";
    case DistortionModel::Fisheye:
        return "equidistant";
    }
    return "none";
}

// A number a person wrote, for a key they read: 90.00000000000001 (atan2's rounding) is 90, while a value that is
// not that close to a short decimal keeps every bit.
double tidy(double value)
{
    const double rounded = roundedTo(value, kTidyDecimals);
    return std::abs(rounded - value) <= kTidySlack * std::max(1.0, std::abs(value)) ? rounded : value;
}

toml::array tidyArray(const glm::dvec3 &v)
{
    return numbers({tidy(v.x), tidy(v.y), tidy(v.z)});
}

// OpenCV's rvec (axis times angle, radians) of a rotation matrix, by its quaternion: no branch near 180 degrees.
glm::dvec3 rodriguesOf(const glm::dmat3 &rotation)
{
    glm::dquat q = glm::quat_cast(rotation);
    if (q.w < 0.0)
        q = -q;
    const glm::dvec3 axis(q.x, q.y, q.z);
    const double sine = glm::length(axis);
    if (sine == 0.0)
        return glm::dvec3(0.0);
    return axis * (2.0 * std::atan2(sine, q.w) / sine);
}

// The pose in the keys the config wrote it in (`yaw = 90.0`, not a matrix the user never wrote): the same units and
// axes, tidied to what a person wrote. The matrix form stays exact: OpenCV's optical axes are the internal axes with
// y and z negated, so the loaded pose equals the live one bit for bit.
void putPose(const CameraSpec &spec, toml::table &camera)
{
    const Pose &pose = spec.pose;
    const glm::dmat3 worldFromInternal = glm::transpose(pose.rotation);
    const glm::dvec3 position = pose.position(), back = worldFromInternal[2];
    // A camera without roll has Z up, as people write it; else its own up, which makes the rolled pose exact.
    const bool level = std::abs(worldFromInternal[0].z) <= kTidySlack && std::abs(back.z) < 1.0 - kTidySlack;
    const glm::dvec3 up = level ? glm::dvec3(0.0, 0.0, 1.0) : worldFromInternal[1];
    const glm::dmat3 flip = internalFromAxes(CameraAxes::Optical); // its own inverse
    switch (spec.poseKeys.form) {
    case PoseForm::LookAt:
        camera.insert_or_assign("eye", tidyArray(position));
        camera.insert_or_assign("target", tidyArray(position - back * spec.poseKeys.targetDistance));
        camera.insert_or_assign("up", tidyArray(up));
        return;
    case PoseForm::Gaze:
        camera.insert_or_assign("eye", tidyArray(position));
        camera.insert_or_assign("gaze", tidyArray(-back));
        camera.insert_or_assign("up", tidyArray(up));
        return;
    case PoseForm::PrpVpnVup:
        camera.insert_or_assign("prp", tidyArray(position));
        camera.insert_or_assign("vpn", tidyArray(back));
        camera.insert_or_assign("vup", tidyArray(up));
        return;
    case PoseForm::Orientation: {
        glm::dquat q = glm::quat_cast(worldFromInternal * internalFromAxes(spec.poseKeys.axes));
        if (q.w < 0.0)
            q = -q; // the same rotation; a leading positive w is how people write it
        camera.insert_or_assign("position", tidyArray(position));
        camera.insert_or_assign("orientation", numbers({tidy(q.w), tidy(q.x), tidy(q.y), tidy(q.z)}));
        camera.insert_or_assign("axes", spec.poseKeys.axes == CameraAxes::Optical  ? "optical"
                                        : spec.poseKeys.axes == CameraAxes::OpenGl ? "opengl"
                                                                                   : "body");
        return;
    }
    case PoseForm::YawPitchRoll: {
        const YawPitchRoll ypr = yawPitchRollOf(pose);
        camera.insert_or_assign("position", tidyArray(position));
        camera.insert_or_assign("yaw", tidy(ypr.yawDeg));
        camera.insert_or_assign("pitch", tidy(ypr.pitchDeg));
        camera.insert_or_assign("roll", tidy(ypr.rollDeg));
        return;
    }
    case PoseForm::Rodrigues:
        camera.insert_or_assign("rvec", vectorArray(rodriguesOf(flip * pose.rotation)));
        camera.insert_or_assign("tvec", vectorArray(flip * pose.translation));
        return;
    case PoseForm::Rt:
        break;
    }
    const glm::dmat3 r = flip * pose.rotation;
    toml::array rows;
    for (int row = 0; row < 3; ++row)
        rows.push_back(numbers({r[0][row], r[1][row], r[2][row]}));
    camera.insert_or_assign("rmat", std::move(rows));
    camera.insert_or_assign("tvec", vectorArray(flip * pose.translation));
}

void putIntrinsicsForm(const CameraSpec &spec, toml::table &camera)
{
    switch (spec.form) {
    case IntrinsicsForm::FieldOfView:
        camera.insert_or_assign("fov", spec.fovDeg);
        camera.insert_or_assign("fov_axis", spec.fovAxis == FovAxis::Vertical ? "vertical" : "horizontal");
        return;
    case IntrinsicsForm::Frustum:
        camera.insert_or_assign("frustum", boundsTable(spec.bounds));
        return;
    case IntrinsicsForm::Pinhole: {
        const PinholeIntrinsics &p = spec.pinhole;
        toml::table pinhole{{"fx", p.fx}, {"fy", p.fy}, {"cx", p.cx}, {"cy", p.cy}, {"skew", p.skew}};
        if (p.width > 0) {
            pinhole.insert_or_assign("width", int64_t(p.width));
            pinhole.insert_or_assign("height", int64_t(p.height));
        }
        camera.insert_or_assign("pinhole", std::move(pinhole));
        return;
    }
    case IntrinsicsForm::Window: {
        const WindowIntrinsics &w = spec.window;
        camera.insert_or_assign("window", toml::table{{"focal", w.focal},
                                                      {"centre", numbers({w.centre.x, w.centre.y})},
                                                      {"half_width", w.halfWidth},
                                                      {"half_height", w.halfHeight}});
        return;
    }
    case IntrinsicsForm::Orthographic:
        camera.insert_or_assign("orthographic", boundsTable(spec.bounds));
        return;
    case IntrinsicsForm::WindowOrthographic: {
        toml::table box = boundsTable(spec.bounds);
        box.insert_or_assign("width", spec.orthoSize.x);
        box.insert_or_assign("height", spec.orthoSize.y);
        camera.insert_or_assign("orthographic", std::move(box));
        return;
    }
    }
}

// Every camera key the API or a calibration can set, so that nothing of the live camera is left to the main file.
void putCamera(const CameraSpec &spec, toml::table &camera)
{
    for (std::string_view key : kPoseKeys)
        camera.erase(key);
    for (std::string_view key : kIntrinsicsFormKeys)
        camera.erase(key);
    camera.erase("calibration"); // its pinhole and distortion are written out below
    putPose(spec, camera);
    putIntrinsicsForm(spec, camera);
    if (spec.calibrationCrop == CalibrationCrop::Region) {
        const CalibrationRegion &r = spec.calibrationRegion;
        camera.insert_or_assign("calibration_crop", numbers({r.x, r.y, r.width, r.height}));
    } else {
        camera.insert_or_assign("calibration_crop",
                                spec.calibrationCrop == CalibrationCrop::Center ? "center" : "none");
    }
    camera.insert_or_assign("near", spec.near);
    if (spec.far == kInfiniteFar)
        camera.insert_or_assign("far", "inf");
    else
        camera.insert_or_assign("far", spec.far);
    camera.insert_or_assign("depth_range", spec.depth == DepthRange::ZeroToOne ? "0..1" : "-1..1");
    toml::table distortion{{"model", distortionModelName(spec.distortion.model)}};
    const int count = coefficientCount(spec.distortion.model);
    if (count > 0) {
        toml::array coefficients;
        for (int i = 0; i < count; ++i)
            coefficients.push_back(spec.distortion.coeffs[size_t(i)]);
        distortion.insert_or_assign("coefficients", std::move(coefficients));
    }
    if (spec.distortion.fieldDeg > 0.0)
        distortion.insert_or_assign("max_field_deg", spec.distortion.fieldDeg);
    camera.insert_or_assign("distortion", std::move(distortion));
}

Result<toml::table> parseExisting(std::string_view existing, const std::string &dropInName)
{
    if (auto deep = findTooDeep(existing, TextSyntax::Toml))
        return makeError(ErrorCode::ConfigError,
                         dropInName + ":" + std::to_string(deep->line) + ": nested too deep; not saved over it");
    try {
        return toml::parse(existing, dropInName);
    } catch (const toml::parse_error &e) {
        return makeError(ErrorCode::ConfigError, dropInName + ":" + std::to_string(e.source().begin.line) +
                                                     ": syntax error: " + std::string(e.description()) +
                                                     "; not saved over it");
    }
}

} // namespace

std::string liveDropInPath(const std::string &configPath)
{
    std::filesystem::path path(configPath);
    const std::string stem = path.extension() == ".toml" ? path.stem().string() : path.filename().string();
    return (path.parent_path() / (stem + ".live.toml")).string();
}

Result<std::string> liveDropInText(const CameraSpec &camera, std::string_view existing, std::string_view writer,
                                   const std::string &dropInName)
{
    auto root = parseExisting(existing, dropInName);
    if (!root)
        return root.error();
    toml::table merged;
    if (const toml::table *kept = (*root)["camera"].as_table())
        merged = *kept;
    putCamera(camera, merged);

    const YawPitchRoll ypr = yawPitchRollOf(camera.pose);
    std::string text =
        "# Written by overlayd (" + std::string(writer) +
        "): the live camera, read after the main config file; its keys replace the main file's.\n"
        "# Delete this file to go back to the main file's camera.\n"
        "# The pose in the mount frame '" +
        camera.mountFrame + "': position = " +
        tomlText(numbers({roundedTo(ypr.position.x, kCommentDecimals), roundedTo(ypr.position.y, kCommentDecimals),
                          roundedTo(ypr.position.z, kCommentDecimals)})) +
        ", yaw = " + numberText(roundedTo(ypr.yawDeg, kCommentDecimals)) +
        ", pitch = " + numberText(roundedTo(ypr.pitchDeg, kCommentDecimals)) +
        ", roll = " + numberText(roundedTo(ypr.rollDeg, kCommentDecimals)) + " (degrees)\n";
    for (const auto &[key, value] : *root)
        if (key.str() != "camera")
            text += keyText(key.str()) + " = " + tomlText(value) + "\n";
    text += "[camera]\n";
    for (const auto &[key, value] : merged)
        text += keyText(key.str()) + " = " + tomlText(value) + "\n";
    return text;
}

Result<std::string> writeLiveDropIn(const std::string &configPath, const CameraSpec &camera, std::string_view writer)
{
    const std::string path = liveDropInPath(configPath);
    std::string existing;
    if (auto read = readRegularFile(path, kMaxConfigFileBytes))
        existing = std::move(*read);
    else if (read.error().code != ErrorCode::NotFound)
        return makeError(ErrorCode::Io, path + ": the drop-in " + read.error().message + "; not saved over it");
    auto text = liveDropInText(camera, existing, writer, path);
    if (!text)
        return text.error();
    if (auto replaced = replaceFileContents(path, *text); !replaced)
        return replaced.error();
    return path;
}

} // namespace overlayd
