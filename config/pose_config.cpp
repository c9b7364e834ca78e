// SPDX-License-Identifier: Apache-2.0
// [camera] pose keys: every pose form of projection/pose.h, chosen by the key only that form has.
#include "config/config_sections.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "projection/pose.h"

namespace overlayd {

namespace {

struct PoseFormInfo {
    PoseForm form;
    const char *name;
    std::array<std::string_view, 3> markers; // any of these selects the form
    std::array<std::string_view, 4> keys;    // every key the form uses
};

constexpr PoseFormInfo kPoseForms[] = {
    {PoseForm::LookAt, "eye/target/up", {"target"}, {"eye", "target", "up"}},
    {PoseForm::Gaze, "eye/gaze/up", {"gaze"}, {"eye", "gaze", "up"}},
    {PoseForm::PrpVpnVup, "prp/vpn/vup", {"prp", "vpn", "vup"}, {"prp", "vpn", "vup"}},
    {PoseForm::Orientation, "position/orientation/axes", {"orientation", "axes"}, {"position", "orientation", "axes"}},
    {PoseForm::YawPitchRoll, "position/yaw/pitch/roll", {"yaw", "pitch", "roll"}, {"position", "yaw", "pitch", "roll"}},
    {PoseForm::Rodrigues, "rvec/tvec", {"rvec"}, {"rvec", "tvec"}},
    {PoseForm::Rt, "rmat/tvec", {"rmat"}, {"rmat", "tvec"}},
};

bool uses(const PoseFormInfo &info, std::string_view key)
{
    return std::find(info.keys.begin(), info.keys.end(), key) != info.keys.end();
}

// The form whose marker keys are present; nullptr after a problem (none or several).
const PoseFormInfo *chooseForm(TableReader &camera)
{
    std::vector<const PoseFormInfo *> chosen;
    for (const PoseFormInfo &info : kPoseForms)
        for (std::string_view marker : info.markers)
            if (!marker.empty() && camera.has(marker)) {
                chosen.push_back(&info);
                break;
            }
    if (chosen.size() == 1)
        return chosen.front();
    if (chosen.empty()) {
        camera.problemAtTable("no camera pose: give eye+target, eye+gaze, prp+vpn, position+orientation, "
                              "position+yaw/pitch/roll, rvec+tvec or rmat+tvec");
        return nullptr;
    }
    std::string names;
    for (const PoseFormInfo *info : chosen)
        names += std::string(names.empty() ? "" : " and ") + info->name;
    camera.problemAtTable("two pose forms given (" + names + "); give one");
    return nullptr;
}

std::optional<glm::dvec3> required(TableReader &camera, std::string_view key, const char *form)
{
    if (!camera.has(key)) {
        camera.problem(key, std::string("missing: the ") + form + " pose form needs it");
        return std::nullopt;
    }
    return camera.vec3(key);
}

// Rows: [[r00, r01, r02], [r10, r11, r12], [r20, r21, r22]].
std::optional<glm::dmat3> readMatrix3(TableReader &camera, std::string_view key)
{
    const toml::node *n = camera.node(key);
    if (!n)
        return std::nullopt;
    const toml::array *rows = n->as_array();
    glm::dmat3 m(0.0);
    bool ok = rows && rows->size() == 3;
    for (size_t r = 0; ok && r < 3; ++r) {
        const toml::array *row = rows->get(r)->as_array();
        ok = row && row->size() == 3;
        for (size_t c = 0; ok && c < 3; ++c) {
            const auto v = row->get(c)->value<double>();
            ok = v && std::isfinite(*v);
            m[int(c)][int(r)] = ok ? *v : 0.0;
        }
    }
    if (!ok) {
        camera.problem(key, "expected a 3x3 matrix of finite numbers [[r00, r01, r02], [r10, ...], [r20, ...]]");
        return std::nullopt;
    }
    return m;
}

std::optional<CameraAxes> readAxes(TableReader &camera)
{
    if (!camera.has("axes"))
        return CameraAxes::Body;
    return camera.choice<CameraAxes>(
        "axes", {{"body", CameraAxes::Body}, {"optical", CameraAxes::Optical}, {"opengl", CameraAxes::OpenGl}});
}

// nullopt after a missing or invalid input (already reported); else the builder's result.
std::optional<Result<Pose>> buildPose(TableReader &camera, PoseForm form, const char *name)
{
    const glm::dvec3 zUp(0.0, 0.0, 1.0);
    switch (form) {
    case PoseForm::LookAt:
    case PoseForm::Gaze: {
        const char *second = form == PoseForm::LookAt ? "target" : "gaze";
        const auto eye = required(camera, "eye", name), other = required(camera, second, name);
        const auto up = camera.has("up") ? camera.vec3("up") : std::optional(zUp);
        if (!eye || !other || !up)
            return std::nullopt;
        return form == PoseForm::LookAt ? poseLookAt(*eye, *other, *up) : poseFromGaze(*eye, *other, *up);
    }
    case PoseForm::PrpVpnVup: {
        const auto prp = required(camera, "prp", name), vpn = required(camera, "vpn", name);
        const auto vup = camera.has("vup") ? camera.vec3("vup") : std::optional(zUp);
        if (!prp || !vpn || !vup)
            return std::nullopt;
        return poseFromPrpVpnVup(*prp, *vpn, *vup);
    }
    case PoseForm::Orientation: {
        const auto position = required(camera, "position", name);
        const auto axes = readAxes(camera);
        if (!camera.has("orientation"))
            camera.problem("orientation", std::string("missing: the ") + name + " pose form needs it");
        const auto q = camera.quaternion("orientation");
        if (!position || !axes || !q)
            return std::nullopt;
        return poseFromOrientation(*position, *q, *axes);
    }
    case PoseForm::YawPitchRoll: {
        const auto position = required(camera, "position", name);
        const auto yaw = camera.number("yaw", -360, 360), pitch = camera.number("pitch", -360, 360),
                   roll = camera.number("roll", -360, 360);
        if (!position || (camera.has("yaw") && !yaw) || (camera.has("pitch") && !pitch) ||
            (camera.has("roll") && !roll))
            return std::nullopt;
        return poseFromYawPitchRoll(*position, yaw.value_or(0.0), pitch.value_or(0.0), roll.value_or(0.0));
    }
    case PoseForm::Rodrigues:
    case PoseForm::Rt: {
        const auto tvec = required(camera, "tvec", name);
        if (form == PoseForm::Rodrigues) {
            const auto rvec = camera.vec3("rvec");
            if (!rvec || !tvec)
                return std::nullopt;
            return poseFromRodrigues(*rvec, *tvec);
        }
        const auto rmat = readMatrix3(camera, "rmat");
        if (!rmat || !tvec)
            return std::nullopt;
        return poseFromRt(*rmat, *tvec);
    }
    }
    return std::nullopt;
}

// The key a builder's complaint is about: the up vector for degenerate bases, else the form's marker.
std::string_view blamedKey(TableReader &camera, const PoseFormInfo &info, const Error &error)
{
    if (error.code == ErrorCode::DegenerateBasis) {
        for (std::string_view up : {"up", "vup"})
            if (uses(info, up) && camera.has(up))
                return up;
    }
    for (std::string_view marker : info.markers)
        if (!marker.empty() && camera.has(marker))
            return marker;
    return info.keys.front();
}

} // namespace

bool readPose(TableReader &camera, Pose &out, PoseKeysUsed *used)
{
    const PoseFormInfo *info = chooseForm(camera);
    for (std::string_view key : kPoseKeys)
        if (camera.has(key) && info && !uses(*info, key))
            camera.problem(key, std::string("does not belong to the ") + info->name + " pose form in use");
    if (!info)
        return false;
    const auto pose = buildPose(camera, info->form, info->name);
    if (!pose)
        return false;
    if (!*pose) {
        camera.problem(blamedKey(camera, *info, pose->error()), pose->error().message);
        return false;
    }
    out = pose->value();
    if (used) {
        used->form = info->form;
        if (info->form == PoseForm::Orientation)
            used->axes = readAxes(camera).value_or(CameraAxes::Body);
        if (info->form == PoseForm::LookAt)
            used->targetDistance = glm::distance(*camera.vec3("eye"), *camera.vec3("target"));
    }
    return true;
}

} // namespace overlayd
