// SPDX-License-Identifier: Apache-2.0
// Controls: the registry answers what check-config can know; the camera's ControlInfoMap what only it knows.
#include "drivers/libcamera/libcamera_controls.h"

#include <cfloat>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <optional>

#include <libcamera/control_ids.h>

namespace overlayd {

namespace {

const libcamera::ControlId *registryControl(const std::string &name)
{
    for (const auto &[id, control] : libcamera::controls::controls) {
        if (control->name() == name)
            return control;
    }
    return nullptr;
}

// Whether the control takes an array. ControlId::isArray() is not in libcamera 0.3.2; there, the
// table's array controls (the Span<> ones of 0.3.2's control_ids.h) are named.
template<typename Id>
bool isArrayControl(const Id &id)
{
    if constexpr (requires { id.isArray(); }) {
        return id.isArray();
    } else {
        namespace c = libcamera::controls;
        for (const libcamera::ControlId *array : std::initializer_list<const libcamera::ControlId *>{
                 &c::ColourGains, &c::SensorBlackLevels, &c::ColourCorrectionMatrix, &c::FrameDurationLimits,
                 &c::AfWindows})
            if (&id == array)
                return true;
        return false;
    }
}

} // namespace

std::vector<std::string> libcameraControlNames()
{
    std::vector<std::string> names;
    for (const auto &[id, control] : libcamera::controls::controls)
        names.push_back(control->name());
    return names;
}

std::optional<ControlValueKind> libcameraControlKind(const std::string &name)
{
    const libcamera::ControlId *control = registryControl(name);
    if (!control)
        return std::nullopt;
    switch (control->type()) {
    case libcamera::ControlTypeBool:
        return ControlValueKind::Bool;
    case libcamera::ControlTypeByte:
    case libcamera::ControlTypeInteger32:
    case libcamera::ControlTypeInteger64:
        return ControlValueKind::Integer;
    case libcamera::ControlTypeFloat:
        return ControlValueKind::Float;
    default:
        return ControlValueKind::Unsupported;
    }
}

namespace {

// The config value as the control's type, or the reason it can never be one, whatever the camera.
Result<libcamera::ControlValue> toControlValue(const libcamera::ControlId &id, const ControlSetting &setting)
{
    if (isArrayControl(id))
        return makeError(ErrorCode::ConfigError, "an array control: not settable from the config");
    const auto *integer = std::get_if<int64_t>(&setting.value);
    const auto *real = std::get_if<double>(&setting.value);
    switch (id.type()) {
    case libcamera::ControlTypeBool:
        if (const auto *b = std::get_if<bool>(&setting.value))
            return libcamera::ControlValue(*b);
        break;
    case libcamera::ControlTypeByte:
        if (integer && *integer >= 0 && *integer <= 255)
            return libcamera::ControlValue(uint8_t(*integer));
        break;
    case libcamera::ControlTypeInteger32:
        if (integer && *integer >= INT32_MIN && *integer <= INT32_MAX)
            return libcamera::ControlValue(int32_t(*integer));
        break;
    case libcamera::ControlTypeInteger64:
        if (integer)
            return libcamera::ControlValue(*integer);
        break;
    case libcamera::ControlTypeFloat:
        if (real && std::isnan(*real))
            return makeError(ErrorCode::ConfigError, "not a number (nan): expected a number");
        if (real && std::abs(*real) <= FLT_MAX)
            return libcamera::ControlValue(float(*real));
        break;
    default:
        break;
    }
    const char *wanted = id.type() == libcamera::ControlTypeBool        ? "true or false"
                         : id.type() == libcamera::ControlTypeByte      ? "an integer 0..255"
                         : id.type() == libcamera::ControlTypeInteger32 ? "a 32-bit integer (-2147483648..2147483647)"
                         : id.type() == libcamera::ControlTypeInteger64 ? "an integer"
                         : id.type() == libcamera::ControlTypeFloat     ? "a finite number within a float's range "
                                                                          "(+-3.4e38)"
                                                                        : "a value a config cannot give";
    return makeError(ErrorCode::ConfigError, std::string("expected ") + wanted);
}

// -1 below, 0 inside, 1 above; nullopt when the two cannot be compared (an array, another type).
std::optional<int> compare(const libcamera::ControlValue &value, const libcamera::ControlValue &bound)
{
    if (bound.isNone() || bound.isArray() || bound.type() != value.type())
        return std::nullopt;
    const auto order = [](auto a, auto b) {
        return a < b ? -1 : a > b ? 1 : 0;
    };
    switch (value.type()) {
    case libcamera::ControlTypeBool:
        return order(value.get<bool>(), bound.get<bool>());
    case libcamera::ControlTypeByte:
        return order(value.get<uint8_t>(), bound.get<uint8_t>());
    case libcamera::ControlTypeInteger32:
        return order(value.get<int32_t>(), bound.get<int32_t>());
    case libcamera::ControlTypeInteger64:
        return order(value.get<int64_t>(), bound.get<int64_t>());
    case libcamera::ControlTypeFloat:
        return order(value.get<float>(), bound.get<float>());
    default:
        return std::nullopt;
    }
}

std::string checkRange(const libcamera::ControlValue &value, const libcamera::ControlInfo &info)
{
    if (info.min().isArray() || info.max().isArray())
        return "an array control: not settable from the config";
    const auto low = compare(value, info.min()), high = compare(value, info.max());
    if ((low && *low < 0) || (high && *high > 0))
        return value.toString() + " is outside " + info.min().toString() + ".." + info.max().toString() +
               " (this camera's range)";
    return {};
}

} // namespace

std::string libcameraControlProblem(const ControlSetting &setting)
{
    const libcamera::ControlId *id = registryControl(setting.name);
    if (!id)
        return "unknown libcamera control";
    const auto value = toControlValue(*id, setting);
    return value ? std::string() : value.error().message;
}

Result<libcamera::ControlList> buildControls(const std::vector<ControlSetting> &settings,
                                             const libcamera::ControlInfoMap &camera)
{
    libcamera::ControlList list(camera);
    std::string problems;
    const auto problem = [&](const ControlSetting &s, const std::string &message) {
        problems += (problems.empty() ? "" : "\n") + s.where + ": " + message;
    };
    for (const ControlSetting &setting : settings) {
        const libcamera::ControlId *id = registryControl(setting.name);
        const auto info = id ? camera.find(id->id()) : camera.end();
        if (!id || info == camera.end()) {
            problem(setting, "this camera has no control " + setting.name);
            continue;
        }
        auto value = toControlValue(*id, setting);
        if (!value) {
            problem(setting, value.error().message);
            continue;
        }
        if (const std::string outside = checkRange(*value, info->second); !outside.empty()) {
            problem(setting, outside);
            continue;
        }
        list.set(id->id(), *value);
    }
    if (!problems.empty())
        return makeError(ErrorCode::ConfigError, problems);
    return list;
}

} // namespace overlayd
