// CameraSpec::build: the configured camera, composed through projection/ for one stream size.
#include "config/camera_spec.h"

#include <algorithm>
#include <cmath>
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

} // namespace

Result<PinholeIntrinsics> CameraSpec::scaledPinhole(const Viewport &vp) const
{
    PinholeIntrinsics k = pinhole;
    const int width = vp.window().width, height = vp.window().height;
    if (k.width <= 0 || k.height <= 0) { // no image size given: the intrinsics are for this stream's window
        k.width = width;
        k.height = height;
    }
    if (k.width == width && k.height == height)
        return k;
    CalibrationWindow w;
    if (sameAspect(k, width, height)) {
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
    if (form != IntrinsicsForm::Pinhole || pinhole.width <= 0 || pinhole.height <= 0 ||
        (pinhole.width == vp.window().width && pinhole.height == vp.window().height))
        return {};
    const auto scaled = scaledPinhole(vp);
    if (!scaled)
        return {};
    const bool cropped = !sameAspect(pinhole, vp.window().width, vp.window().height);
    return "camera: intrinsics calibrated at " + sizeText(pinhole.width, pinhole.height) + " " +
           (cropped ? "cropped to the centre and scaled" : "scaled") + " to the " +
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
    case IntrinsicsForm::Seed000Orthographic:
        return Projection::seed000Orthographic(orthoSize.x, orthoSize.y, near, far, depth);
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
