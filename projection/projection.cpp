// SPDX-License-Identifier: Apache-2.0
// Projection builders. Matrices follow GLM's right-handed *_NO / *_ZO conventions (column-major m[col][row]).
#include "projection.h"

#include <cmath>

#include "checks.h"
#include "viewing_pipeline.h"

namespace overlayd {

double ndcNearDepth(DepthRange depth)
{
    return depth == DepthRange::MinusOneToOne ? -1.0 : 0.0;
}

namespace {

Status checkNearFar(double near, double far, bool allowInfiniteFar)
{
    if (!std::isfinite(near) || std::isnan(far) || (!allowInfiniteFar && std::isinf(far)))
        return makeError(ErrorCode::InvalidArgument, "near and far must be finite numbers");
    if (near <= 0.0)
        return makeError(ErrorCode::InvalidArgument, "near must be > 0 (got " + Checks::str(near) + ")");
    if (far <= near)
        return makeError(ErrorCode::InvalidArgument, "far must be greater than near (near " + Checks::str(near) +
                                                         ", far " + Checks::str(far) + ")");
    return Ok{};
}

// The depth rows of a perspective matrix: z_clip = a z + b, w_clip = -z, so that near -> ndcNearDepth, far -> 1.
void setPerspectiveDepth(glm::dmat4 &m, double near, double far, DepthRange depth)
{
    m[2][3] = -1.0;
    m[3][3] = 0.0;
    const bool zeroToOne = depth == DepthRange::ZeroToOne;
    if (std::isinf(far)) { // the limit far -> infinity
        m[2][2] = -1.0;
        m[3][2] = zeroToOne ? -near : -2.0 * near;
    } else if (zeroToOne) {
        m[2][2] = far / (near - far);
        m[3][2] = -(far * near) / (far - near);
    } else {
        m[2][2] = -(far + near) / (far - near);
        m[3][2] = -(2.0 * far * near) / (far - near);
    }
}

glm::dmat4 zeroToOneToMinusOneToOne()
{
    glm::dmat4 remap(1.0);
    remap[2][2] = 2.0;
    remap[3][2] = -1.0;
    return remap;
}

} // namespace

Result<Projection> Projection::perspective(FovAxis axis, double fovDeg, double aspect, double near, double far,
                                           DepthRange depth)
{
    if (!std::isfinite(fovDeg) || fovDeg <= 0.0 || fovDeg >= 180.0)
        return makeError(ErrorCode::InvalidArgument,
                         "field of view must be in (0, 180) degrees (got " + Checks::str(fovDeg) + ")");
    if (!std::isfinite(aspect) || aspect <= 0.0)
        return makeError(ErrorCode::InvalidArgument, "aspect must be > 0 (got " + Checks::str(aspect) + ")");
    if (auto status = checkNearFar(near, far, true); !status)
        return status.error();
    const double tanHalf = std::tan(fovDeg * M_PI / 360.0);
    const double tanHalfY = axis == FovAxis::Vertical ? tanHalf : tanHalf / aspect;
    glm::dmat4 m(0.0);
    m[0][0] = 1.0 / (aspect * tanHalfY);
    m[1][1] = 1.0 / tanHalfY;
    setPerspectiveDepth(m, near, far, depth);
    return Projection(m, depth, true, std::isfinite(far));
}

Result<Projection> Projection::frustum(const FrustumBounds &b, DepthRange depth)
{
    if (!std::isfinite(b.left) || !std::isfinite(b.right) || !std::isfinite(b.bottom) || !std::isfinite(b.top))
        return makeError(ErrorCode::InvalidArgument, "frustum left, right, bottom and top must be finite");
    if (b.right <= b.left || b.top <= b.bottom)
        return makeError(ErrorCode::InvalidArgument, "frustum must have right > left and top > bottom");
    if (auto status = checkNearFar(b.near, b.far, true); !status)
        return status.error();
    glm::dmat4 m(0.0);
    m[0][0] = 2.0 * b.near / (b.right - b.left);
    m[1][1] = 2.0 * b.near / (b.top - b.bottom);
    m[2][0] = (b.right + b.left) / (b.right - b.left);
    m[2][1] = (b.top + b.bottom) / (b.top - b.bottom);
    setPerspectiveDepth(m, b.near, b.far, depth);
    return Projection(m, depth, true, std::isfinite(b.far));
}

Result<Projection> Projection::orthographic(const FrustumBounds &b, DepthRange depth)
{
    const bool finite = std::isfinite(b.left) && std::isfinite(b.right) && std::isfinite(b.bottom) &&
                        std::isfinite(b.top) && std::isfinite(b.near) && std::isfinite(b.far);
    if (!finite)
        return makeError(ErrorCode::InvalidArgument, "orthographic box bounds must be finite");
    if (b.right <= b.left || b.top <= b.bottom)
        return makeError(ErrorCode::InvalidArgument, "orthographic box must have right > left and top > bottom");
    // A parallel projection has no centre of projection, so near may be zero or negative; the box must not be flat.
    if (b.far <= b.near)
        return makeError(ErrorCode::InvalidArgument, "far must be greater than near (near " + Checks::str(b.near) +
                                                         ", far " + Checks::str(b.far) + ")");
    glm::dmat4 m(1.0);
    m[0][0] = 2.0 / (b.right - b.left);
    m[1][1] = 2.0 / (b.top - b.bottom);
    m[3][0] = -(b.right + b.left) / (b.right - b.left);
    m[3][1] = -(b.top + b.bottom) / (b.top - b.bottom);
    if (depth == DepthRange::ZeroToOne) {
        m[2][2] = -1.0 / (b.far - b.near);
        m[3][2] = -b.near / (b.far - b.near);
    } else {
        m[2][2] = -2.0 / (b.far - b.near);
        m[3][2] = -(b.far + b.near) / (b.far - b.near);
    }
    return Projection(m, depth, false, true);
}

Result<Projection> Projection::pinhole(const PinholeIntrinsics &k, double near, double far, DepthRange depth)
{
    if (!std::isfinite(k.fx) || !std::isfinite(k.fy) || !std::isfinite(k.cx) || !std::isfinite(k.cy) ||
        !std::isfinite(k.skew))
        return makeError(ErrorCode::InvalidArgument, "camera matrix entries must be finite");
    if (k.fx <= 0.0 || k.fy <= 0.0)
        return makeError(ErrorCode::InvalidArgument,
                         "focal lengths fx, fy must be > 0 (got " + Checks::str(k.fx) + ", " + Checks::str(k.fy) + ")");
    if (k.width <= 0 || k.height <= 0)
        return makeError(ErrorCode::InvalidArgument, "pinhole image size must be positive (got " +
                                                         std::to_string(k.width) + "x" + std::to_string(k.height) +
                                                         ")");
    if (auto status = checkNearFar(near, far, true); !status)
        return status.error();
    // Pixel centres sit at integers, so the image spans [-0.5, width - 0.5]: NDC x = (2 (u + 0.5) / width) - 1,
    // NDC y = 1 - 2 (v + 0.5) / height (rows grow downwards, NDC y upwards). With x = X/-Z, y = -Y/-Z in the
    // internal frame this gives the matrix below; it equals frustum() with l = -(cx + 0.5) near / fx, etc.
    const double w = k.width, h = k.height;
    glm::dmat4 m(0.0);
    m[0][0] = 2.0 * k.fx / w;
    m[1][0] = -2.0 * k.skew / w;
    m[2][0] = 1.0 - 2.0 * (k.cx + 0.5) / w;
    m[1][1] = 2.0 * k.fy / h;
    m[2][1] = 2.0 * (k.cy + 0.5) / h - 1.0;
    setPerspectiveDepth(m, near, far, depth);
    Projection projection(m, depth, true, std::isfinite(far));
    projection.pinhole_ = k;
    return projection;
}

Result<Projection> Projection::window(const WindowIntrinsics &w, DepthRange depth)
{
    if (!std::isfinite(w.focal) || w.focal <= 0.0)
        return makeError(ErrorCode::InvalidArgument,
                         "window focal length must be > 0 (got " + Checks::str(w.focal) + ")");
    if (!std::isfinite(w.centre.x) || !std::isfinite(w.centre.y))
        return makeError(ErrorCode::InvalidArgument, "window centre must be finite");
    if (!std::isfinite(w.halfWidth) || !std::isfinite(w.halfHeight) || w.halfWidth <= 0.0 || w.halfHeight <= 0.0)
        return makeError(ErrorCode::InvalidArgument, "window half spans must be > 0");
    // S_far needs a finite far plane; use frustum() for an infinite one.
    if (auto status = checkNearFar(w.near, w.far, false); !status)
        return status.error();
    const glm::dvec3 cw(w.centre, -w.focal);
    const glm::dmat4 zeroToOne = ViewingPipeline::perspective(w.near / w.far) * ViewingPipeline::scaleFar(w.far) *
                                 ViewingPipeline::scaleXY(w.focal, 2.0 * w.halfWidth, 2.0 * w.halfHeight) *
                                 ViewingPipeline::shear(cw);
    const glm::dmat4 m = depth == DepthRange::ZeroToOne ? zeroToOne : zeroToOneToMinusOneToOne() * zeroToOne;
    return Projection(m, depth, true, true);
}

Result<Projection> Projection::windowOrthographic(double width, double height, double near, double far,
                                                  DepthRange depth)
{
    if (!std::isfinite(width) || !std::isfinite(height) || width <= 0.0 || height <= 0.0)
        return makeError(ErrorCode::InvalidArgument, "orthographic window width and height must be > 0");
    if (!std::isfinite(near) || !std::isfinite(far) || far <= near)
        return makeError(ErrorCode::InvalidArgument, "far must be greater than near (near " + Checks::str(near) +
                                                         ", far " + Checks::str(far) + ")");
    const glm::dmat4 zeroToOne = ViewingPipeline::orthographic(width, height, near, far);
    const glm::dmat4 m = depth == DepthRange::ZeroToOne ? zeroToOne : zeroToOneToMinusOneToOne() * zeroToOne;
    return Projection(m, depth, false, true);
}

} // namespace overlayd
