// SPDX-License-Identifier: Apache-2.0
// [camera] intrinsics: field of view, frustum, pinhole (or a calibration file), the viewing-pipeline window,
// orthographic; near/far, depth range and lens distortion.
#include "config/config_sections.h"

#include <array>

#include "config/calibration.h"
#include "config/limits.h"

namespace overlayd {

namespace {

struct IntrinsicsFormInfo {
    std::string_view key;
    IntrinsicsForm form;
};
constexpr IntrinsicsFormInfo kIntrinsicsForms[] = {
    {"fov", IntrinsicsForm::FieldOfView},           {"frustum", IntrinsicsForm::Frustum},
    {"pinhole", IntrinsicsForm::Pinhole},           {"window", IntrinsicsForm::Window},
    {"orthographic", IntrinsicsForm::Orthographic},
};

std::optional<Calibration> readCalibration(TableReader &camera, const std::string &baseDirectory)
{
    const auto path = camera.string("calibration");
    if (!path)
        return std::nullopt;
    auto calibration = loadCalibration(resolvePath(baseDirectory, *path));
    if (!calibration) {
        camera.problem("calibration", calibration.error().message);
        return std::nullopt;
    }
    return calibration.value();
}

// The key of the one intrinsics form given, "" for none (the default field of view), nullopt for several.
std::optional<std::string_view> chooseForm(TableReader &camera, bool calibrated)
{
    std::vector<std::string_view> given;
    for (const IntrinsicsFormInfo &info : kIntrinsicsForms)
        if (camera.has(info.key))
            given.push_back(info.key);
    if (calibrated && (given.empty() || given.front() != "pinhole"))
        given.insert(given.begin(), "pinhole");
    if (given.size() > 1) {
        camera.problem(given[1], "two intrinsics forms given ('" + std::string(given[0]) + "' and '" +
                                     std::string(given[1]) + "'" + (calibrated ? ", calibration is pinhole" : "") +
                                     "); give one");
        return std::nullopt;
    }
    return given.empty() ? std::string_view() : given.front();
}

void readBounds(TableReader &table, FrustumBounds &out, bool required)
{
    const std::array<std::pair<std::string_view, double *>, 4> sides{
        {{"left", &out.left}, {"right", &out.right}, {"bottom", &out.bottom}, {"top", &out.top}}};
    for (const auto &[key, value] : sides) {
        if (required && !table.has(key))
            table.problem(key, "missing: left, right, bottom and top are all required");
        if (auto v = table.number(key))
            *value = *v;
    }
}

void readPinhole(TableReader &camera, bool calibrated, PinholeIntrinsics &k)
{
    auto table = camera.table("pinhole");
    if (!table)
        return;
    const std::array<std::pair<std::string_view, double *>, 4> entries{
        {{"fx", &k.fx}, {"fy", &k.fy}, {"cx", &k.cx}, {"cy", &k.cy}}};
    for (const auto &[key, value] : entries) {
        if (!calibrated && !table->has(key))
            table->problem(key, "missing: fx, fy, cx and cy are required without a calibration file");
        if (auto v = key[0] == 'f' ? table->positive(key) : table->number(key))
            *value = *v;
    }
    if (auto skew = table->number("skew"))
        k.skew = *skew;
    if (auto width = table->integer("width", 1, 65536))
        k.width = int(*width);
    if (auto height = table->integer("height", 1, 65536))
        k.height = int(*height);
    // One without the other would leave the calibrated size half set, which the camera reads as "not given":
    // refused at the key that is there, so that what is written is what the camera uses.
    if (table->has("width") != table->has("height"))
        table->problem(table->has("width") ? "width" : "height",
                       "width and height go together: the image size fx, fy, cx and cy were calibrated at");
    table->finish();
}

// calibration_crop = "none" | "center" | [x, y, width, height] (calibrated pixels, as libcamera's ScalerCrop).
// What depends on the stream's size is checked with the camera (CameraSpec::checkCalibrationRegion).
void readCalibrationCrop(TableReader &camera, CameraSpec &out)
{
    const toml::node *node = camera.node("calibration_crop");
    if (!node || !node->is_array()) {
        if (auto crop = camera.choice<CalibrationCrop>(
                "calibration_crop", {{"none", CalibrationCrop::None}, {"center", CalibrationCrop::Center}}))
            out.calibrationCrop = *crop;
        return;
    }
    const auto values = camera.numbers("calibration_crop", 4);
    if (!values)
        return;
    if (values->size() != 4) {
        camera.problem("calibration_crop", "expected \"none\", \"center\" or [x, y, width, height] (4 numbers, "
                                           "calibrated pixels), got " +
                                               std::to_string(values->size()) + " numbers");
        return;
    }
    const CalibrationRegion region{(*values)[0], (*values)[1], (*values)[2], (*values)[3]};
    if (region.x < 0.0 || region.y < 0.0 || !(region.width > 0.0) || !(region.height > 0.0)) {
        camera.problem("calibration_crop", "x and y must be >= 0, width and height > 0");
        return;
    }
    out.calibrationCrop = CalibrationCrop::Region;
    out.calibrationRegion = region;
}

void readForm(TableReader &camera, std::string_view key, CameraSpec &out)
{
    if (key == "fov") {
        if (auto fov = camera.number("fov", kMinFovDeg, 180.0))
            out.fovDeg = *fov;
        if (auto axis = camera.choice<FovAxis>("fov_axis",
                                               {{"vertical", FovAxis::Vertical}, {"horizontal", FovAxis::Horizontal}}))
            out.fovAxis = *axis;
    } else if (key == "frustum" || key == "orthographic") {
        auto table = camera.table(key);
        if (!table)
            return;
        const bool centredWindow = key == "orthographic" && (table->has("width") || table->has("height"));
        if (centredWindow) {
            out.form = IntrinsicsForm::WindowOrthographic;
            out.orthoSize = {table->positive("width").value_or(2.0), table->positive("height").value_or(2.0)};
        }
        readBounds(*table, out.bounds, !centredWindow);
        table->finish();
    } else if (key == "window") {
        auto table = camera.table("window");
        if (!table)
            return;
        for (std::string_view required : {"focal", "half_width", "half_height"})
            if (!table->has(required))
                table->problem(required, "missing: the window needs focal, half_width and half_height");
        out.window.focal = table->positive("focal").value_or(1.0);
        out.window.centre = table->vec2("centre").value_or(glm::dvec2(0.0));
        out.window.halfWidth = table->positive("half_width").value_or(1.0);
        out.window.halfHeight = table->positive("half_height").value_or(1.0);
        table->finish();
    }
}

std::optional<double> readFar(TableReader &camera)
{
    const toml::node *n = camera.node("far");
    if (!n)
        return std::nullopt;
    const auto *text = n->as_string();
    if ((text && text->get() == "inf") || (n->is_floating_point() && *n->value<double>() == kInfiniteFar))
        return kInfiniteFar;
    if (text) {
        camera.problem("far", "expected a distance in metres or \"inf\", got '" + text->get() + "'");
        return std::nullopt;
    }
    return camera.positive("far", kMaxFar);
}

void readDistortion(TableReader &camera, Distortion &out, CameraKeys &keys)
{
    auto table = camera.table("distortion");
    if (!table)
        return;
    keys.hasDistortion = true;
    if (auto model = table->choice<DistortionModel>("model", {{"none", DistortionModel::None},
                                                              {"plumb_bob", DistortionModel::RadialTangential},
                                                              {"rational_polynomial", DistortionModel::Rational},
                                                              {"equidistant", DistortionModel::Fisheye}})) {
        if (*model != out.model && !table->has("coefficients") && *model != DistortionModel::None)
            table->problem("coefficients", "missing: a distortion model needs its coefficients");
        out = Distortion{*model, {}};
    }
    if (auto coefficients = table->numbers("coefficients", kMaxFixedListEntries)) {
        const size_t count = size_t(coefficientCount(out.model));
        if (coefficients->size() > count || (count == 0 && !coefficients->empty()))
            table->problem("coefficients", "model takes " + std::to_string(count) + " coefficients, got " +
                                               std::to_string(coefficients->size()));
        for (size_t i = 0; i < std::min(count, coefficients->size()); ++i)
            out.coeffs[i] = (*coefficients)[i];
        for (size_t i = coefficients->size(); i < out.coeffs.size(); ++i)
            out.coeffs[i] = 0.0;
    }
    if (auto field = table->positive("max_field_deg", kMaxFisheyeFieldDeg)) {
        if (*field >= kMaxFisheyeFieldDeg)
            table->problem("max_field_deg", "out of range: must be in (0, 360) degrees, below a full turn");
        else if (out.model != DistortionModel::Fisheye)
            table->problem("max_field_deg", "only an equidistant (fisheye) lens takes a field of view");
        else
            out.fieldDeg = *field;
    }
    table->finish();
}

} // namespace

void readIntrinsics(TableReader &camera, const std::string &baseDirectory, CameraSpec &out, CameraKeys &keys)
{
    const std::optional<Calibration> calibration = readCalibration(camera, baseDirectory);
    if (calibration) {
        out.pinhole = calibration->pinhole;
        out.distortion = calibration->distortion;
    }
    const bool calibrated = camera.has("calibration");
    const auto form = chooseForm(camera, calibrated);
    if (form && form->empty())
        readForm(camera, "fov", out); // the default field of view; fov_axis may still be given
    else
        camera.node("fov_axis");
    if (form && !form->empty()) {
        keys.intrinsics = calibrated && !camera.has("pinhole") ? "calibration" : std::string(*form);
        for (const IntrinsicsFormInfo &info : kIntrinsicsForms)
            if (info.key == *form)
                out.form = info.form;
        if (*form == "pinhole")
            readPinhole(camera, calibrated, out.pinhole);
        else
            readForm(camera, *form, out);
    }
    readCalibrationCrop(camera, out);
    if (auto near = camera.positive("near"))
        out.near = *near;
    if (auto far = readFar(camera)) {
        out.far = *far;
        const bool orthographic =
            out.form == IntrinsicsForm::Orthographic || out.form == IntrinsicsForm::WindowOrthographic;
        if (orthographic && *far == kInfiniteFar) {
            // Otherwise the projection refuses its box as "not finite", at the form's key: say what is wrong here.
            camera.problem("far", "an orthographic camera needs a finite far plane (\"inf\" is for perspective)");
            out.far = 1000.0;
        }
    }
    if (auto depth = camera.choice<DepthRange>("depth_range",
                                               {{"-1..1", DepthRange::MinusOneToOne}, {"0..1", DepthRange::ZeroToOne}}))
        out.depth = *depth;
    readDistortion(camera, out.distortion, keys);
}

void readViewport(TableReader &viewport, ViewportSpec &out)
{
    if (auto origin =
            viewport.choice<Origin>("origin", {{"top-left", Origin::TopLeft}, {"bottom-left", Origin::BottomLeft}}))
        out.origin = *origin;
    if (auto aspect = viewport.positive("pixel_aspect", 100.0))
        out.pixelAspect = *aspect;
    for (std::string_view key : {"window", "scissor"}) {
        // Each entry within +-kMaxViewportCoordinate: x + width and y + height stay far inside int.
        const auto rect = viewport.numbers(key, 4, Range{-kMaxViewportCoordinate, kMaxViewportCoordinate});
        if (!rect)
            continue;
        if (rect->size() != 4 || (*rect)[2] < 1 || (*rect)[3] < 1) {
            viewport.problem(key, "expected [x, y, width, height] in pixels with a size of at least 1");
            continue;
        }
        const PixelRect r{int((*rect)[0]), int((*rect)[1]), int((*rect)[2]), int((*rect)[3])};
        (key == "window" ? out.window : out.scissor) = r;
    }
    viewport.finish();
}

} // namespace overlayd
