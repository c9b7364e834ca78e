// SPDX-License-Identifier: Apache-2.0
// CameraSpec::build: the configured camera, composed through projection/ for one stream size.
#include "config/camera_spec.h"

#include "base/number_text.h"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <string>

#include <glm/mat4x4.hpp>

namespace overlayd {

Result<Viewport> CameraSpec::buildViewport(unsigned frameWidth, unsigned frameHeight) const
{
    ViewportSpec spec = viewport;
    spec.frameWidth = int(frameWidth);
    spec.frameHeight = int(frameHeight);
    return Viewport::create(spec);
}

namespace {

// The calibrated image's region the stream shows (x0, y0 and size, in calibrated pixels' edge coordinates) and the
// scale from it to the stream, per axis.
struct CalibrationWindow {
    double x0 = 0, y0 = 0, sx = 1, sy = 1;
    bool cropped = false;
};

// Same aspect: the calibrated height scaled by the width's factor lands within a pixel of the window's.
bool sameAspect(const PinholeIntrinsics &k, int width, int height)
{
    return std::abs(double(k.height) * width / k.width - height) < 1.0;
}

std::string sizeText(int width, int height)
{
    const int d = std::gcd(width, height);
    return std::to_string(width) + "x" + std::to_string(height) + " (" + std::to_string(width / d) + ":" +
           std::to_string(height / d) + ")";
}

// The intrinsics as calibrated, with the image size they were made at (the stream's window when not given).
PinholeIntrinsics calibrated(const PinholeIntrinsics &pinhole, const Viewport &vp)
{
    PinholeIntrinsics k = pinhole;
    if (k.width <= 0 || k.height <= 0) {
        k.width = vp.window().width;
        k.height = vp.window().height;
    }
    return k;
}

std::string number(double value)
{
    return shortNumber(value);
}

} // namespace

Status CameraSpec::checkCalibrationRegion(const Viewport &vp) const
{
    if (calibrationCrop != CalibrationCrop::Region || form != IntrinsicsForm::Pinhole)
        return Ok{};
    const PinholeIntrinsics k = calibrated(pinhole, vp);
    const CalibrationRegion &r = calibrationRegion;
    const std::string region =
        "the region [" + number(r.x) + ", " + number(r.y) + ", " + number(r.width) + ", " + number(r.height) + "]";
    if (!(r.width > 0.0) || !(r.height > 0.0))
        return makeError(ErrorCode::InvalidArgument, region + " is empty: width and height must be > 0");
    if (r.x < 0.0 || r.y < 0.0 || r.x + r.width > k.width || r.y + r.height > k.height)
        return makeError(ErrorCode::InvalidArgument,
                         region + " reaches outside the calibrated " + sizeText(k.width, k.height) + " image");
    const int width = vp.window().width, height = vp.window().height;
    if (std::abs(r.height * width / r.width - height) >= 1.0)
        return makeError(ErrorCode::InvalidArgument,
                         region + " is not of the stream's aspect (" + sizeText(width, height) +
                             "): scaled to the stream's width it would be " + number(r.height * width / r.width) +
                             " rows high, not " + std::to_string(height));
    return Ok{};
}

Result<PinholeIntrinsics> CameraSpec::scaledPinhole(const Viewport &vp) const
{
    const PinholeIntrinsics k = calibrated(pinhole, vp);
    const int width = vp.window().width, height = vp.window().height;
    CalibrationWindow w;
    if (calibrationCrop == CalibrationCrop::Region) {
        // Checked before (with the config's keys); here again so that build() alone never makes a wrong camera.
        if (auto status = checkCalibrationRegion(vp); !status)
            return status.error();
        w.x0 = calibrationRegion.x;
        w.y0 = calibrationRegion.y;
        w.sx = width / calibrationRegion.width;
        w.sy = height / calibrationRegion.height;
        w.cropped = true;
    } else if (k.width == width && k.height == height) {
        return k;
    } else if (sameAspect(k, width, height)) {
        w.sx = double(width) / k.width, w.sy = double(height) / k.height;
    } else if (calibrationCrop == CalibrationCrop::Center) {
        // The largest centred region of the stream's aspect, scaled by one factor to the window.
        const double cropWidth = std::min(double(k.width), double(k.height) * width / height);
        w.sx = w.sy = width / cropWidth;
        w.x0 = 0.5 * (k.width - cropWidth);
        w.y0 = 0.5 * (k.height - height / w.sy);
        w.cropped = true;
    } else {
        return makeError(ErrorCode::InvalidArgument,
                         "the intrinsics are for a " + sizeText(k.width, k.height) + " image but the stream is " +
                             sizeText(width, height) +
                             ": another aspect is not a scaling. Say how the stream was cut from the calibrated "
                             "image (calibration_crop = \"center\": its largest centred region, as most sensor "
                             "modes do), or calibrate at the stream's size");
    }
    PinholeIntrinsics out = k;
    out.fx = k.fx * w.sx;
    out.skew = k.skew * w.sx;
    out.cx = (k.cx + 0.5 - w.x0) * w.sx - 0.5;
    out.fy = k.fy * w.sy;
    out.cy = (k.cy + 0.5 - w.y0) * w.sy - 0.5;
    out.width = width;
    out.height = height;
    return out;
}

std::string CameraSpec::calibrationScaling(const Viewport &vp) const
{
    const bool sameSize = pinhole.width == vp.window().width && pinhole.height == vp.window().height;
    if (form != IntrinsicsForm::Pinhole || pinhole.width <= 0 || pinhole.height <= 0 ||
        (sameSize && calibrationCrop != CalibrationCrop::Region))
        return {};
    const auto scaled = scaledPinhole(vp);
    if (!scaled)
        return {};
    const bool cropped = !sameAspect(pinhole, vp.window().width, vp.window().height);
    const char *how = calibrationCrop == CalibrationCrop::Region ? "cropped to calibration_crop and scaled"
                      : cropped                                  ? "cropped to the centre and scaled"
                                                                 : "scaled";
    return "camera: intrinsics calibrated at " + sizeText(pinhole.width, pinhole.height) + " " + how + " to the " +
           sizeText(vp.window().width, vp.window().height) + " stream: fx " + std::to_string(scaled->fx) + ", fy " +
           std::to_string(scaled->fy) + ", cx " + std::to_string(scaled->cx) + ", cy " + std::to_string(scaled->cy);
}

Result<Projection> CameraSpec::buildProjection(const Viewport &vp) const
{
    switch (form) {
    case IntrinsicsForm::FieldOfView:
        return Projection::perspective(fovAxis, fovDeg, vp.windowAspect(), near, far, depth);
    case IntrinsicsForm::Frustum: {
        FrustumBounds b = bounds;
        b.near = near;
        b.far = far;
        return Projection::frustum(b, depth);
    }
    case IntrinsicsForm::Pinhole: {
        auto k = scaledPinhole(vp);
        if (!k)
            return k.error();
        return Projection::pinhole(*k, near, far, depth);
    }
    case IntrinsicsForm::Window: {
        WindowIntrinsics w = window;
        w.near = near;
        w.far = far;
        return Projection::window(w, depth);
    }
    case IntrinsicsForm::Orthographic: {
        FrustumBounds b = bounds;
        b.near = near;
        b.far = far;
        return Projection::orthographic(b, depth);
    }
    case IntrinsicsForm::WindowOrthographic:
        return Projection::windowOrthographic(orthoSize.x, orthoSize.y, near, far, depth);
    }
    return makeError(ErrorCode::Unsupported, "unknown intrinsics form");
}

glm::dmat4 CameraSpec::view() const
{
    return pose.viewMatrix() * glm::inverse(worldFromMount);
}

Result<Camera> CameraSpec::build(unsigned frameWidth, unsigned frameHeight) const
{
    auto vp = buildViewport(frameWidth, frameHeight);
    if (!vp)
        return vp.error();
    auto projection = buildProjection(*vp);
    if (!projection)
        return projection.error();
    return Camera::create(view(), *projection, distortion, *vp);
}

} // namespace overlayd
