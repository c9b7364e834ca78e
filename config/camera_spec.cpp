// CameraSpec::build: the configured camera, composed through projection/ for one stream size.
#include "config/camera_spec.h"

#include <cmath>

#include <glm/mat4x4.hpp>

namespace overlayd {

Result<Viewport> CameraSpec::buildViewport(unsigned frameWidth, unsigned frameHeight) const
{
    ViewportSpec spec = viewport;
    spec.frameWidth = int(frameWidth);
    spec.frameHeight = int(frameHeight);
    return Viewport::create(spec);
}

PinholeIntrinsics CameraSpec::scaledPinhole(const Viewport &vp) const
{
    PinholeIntrinsics k = pinhole;
    if (k.width <= 0 || k.height <= 0) { // no image size given: the intrinsics are for this stream's window
        k.width = vp.window().width;
        k.height = vp.window().height;
    }
    if (k.width == vp.window().width && k.height == vp.window().height)
        return k;
    const double sx = double(vp.window().width) / k.width, sy = double(vp.window().height) / k.height;
    PinholeIntrinsics out = k;
    out.fx = k.fx * sx;
    out.skew = k.skew * sx;
    out.cx = (k.cx + 0.5) * sx - 0.5;
    out.fy = k.fy * sy;
    out.cy = (k.cy + 0.5) * sy - 0.5;
    out.width = vp.window().width;
    out.height = vp.window().height;
    return out;
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
    case IntrinsicsForm::Pinhole:
        return Projection::pinhole(scaledPinhole(vp), near, far, depth);
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
