// SPDX-License-Identifier: Apache-2.0
// Projection (intrinsics): every form users give, converging on one 4x4 matrix from camera to clip space.
#pragma once

#include <limits>
#include <optional>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>

#include "base/result.h"

namespace overlayd {

// NDC depth convention: OpenGL's [-1, 1] or [0, 1] (the viewing pipeline's window model, Vulkan, Direct3D).
enum class DepthRange { MinusOneToOne, ZeroToOne };
enum class FovAxis { Vertical, Horizontal };

inline constexpr double kInfiniteFar = std::numeric_limits<double>::infinity();

// A box or frustum in camera coordinates: l, r, b, t on the near plane; near and far are
// positive distances along the viewing direction. far may be kInfiniteFar for perspective frusta.
struct FrustumBounds {
    double left = 0, right = 0, bottom = 0, top = 0, near = 0, far = 0;

    bool operator==(const FrustumBounds &) const = default;
};

// What a calibration produces (OpenCV/ROS): u = fx x + skew y + cx, v = fy y + cy for x = X/Z, y = Y/Z in the
// optical frame, pixels in an image of width x height with pixel (0,0)'s centre at (0,0).
struct PinholeIntrinsics {
    double fx = 0, fy = 0, cx = 0, cy = 0, skew = 0;
    int width = 0, height = 0;

    bool operator==(const PinholeIntrinsics &) const = default;
};

// The viewing pipeline's window model: a window of 2*halfWidth x 2*halfHeight at distance focal along the view
// direction, its centre offset by (centre.x, centre.y) from the optical axis (CW = (centre, -focal) in camera
// coordinates).
struct WindowIntrinsics {
    double focal = 0;
    glm::dvec2 centre{0.0};
    double halfWidth = 0, halfHeight = 0;
    double near = 0, far = 0;

    bool operator==(const WindowIntrinsics &) const = default;
};

class Projection
{
public:
    // gluPerspective: fov in degrees across `axis`, aspect = width / height of the window.
    static Result<Projection> perspective(FovAxis axis, double fovDeg, double aspect, double near, double far,
                                          DepthRange depth);
    // glFrustum, possibly off-axis; far may be kInfiniteFar.
    static Result<Projection> frustum(const FrustumBounds &bounds, DepthRange depth);
    // The viewing pipeline's M_orth for the box [l,r] x [b,t] x [-near,-far] (glOrtho).
    static Result<Projection> orthographic(const FrustumBounds &bounds, DepthRange depth);
    // Calibrated pinhole intrinsics; the image of width x height fills NDC [-1,1]^2 exactly.
    static Result<Projection> pinhole(const PinholeIntrinsics &k, double near, double far, DepthRange depth);
    // The viewing pipeline's window model, composed step by step: P_persp S_far S_xy H.
    static Result<Projection> window(const WindowIntrinsics &w, DepthRange depth);
    // The viewing pipeline's parallel alternative P_o = S_xyz T_near for a centred width x height window.
    static Result<Projection> windowOrthographic(double width, double height, double near, double far,
                                                 DepthRange depth);

    const glm::dmat4 &matrix() const { return matrix_; }
    DepthRange depthRange() const { return depth_; }
    bool isPerspective() const { return perspective_; }
    bool hasFarPlane() const { return hasFar_; }
    // Set for the pinhole form only: lens distortion is defined relative to these.
    const std::optional<PinholeIntrinsics> &pinholeIntrinsics() const { return pinhole_; }

private:
    Projection(const glm::dmat4 &matrix, DepthRange depth, bool perspective, bool hasFar)
        : matrix_(matrix), depth_(depth), perspective_(perspective), hasFar_(hasFar)
    {}

    glm::dmat4 matrix_;
    DepthRange depth_;
    bool perspective_;
    bool hasFar_;
    std::optional<PinholeIntrinsics> pinhole_;
};

// The NDC depth of the near plane (-1 or 0) and of the far plane (1).
double ndcNearDepth(DepthRange depth);

} // namespace overlayd
