// The camera: pose, projection, optional lens and viewport, composed once; projects, clips and unprojects.
//
// The pipeline for a world point X (homogeneous, so directions at infinity project too):
//   clip = P * V * X  ->  clip against near/far (and side/lens planes for lines), never dividing by w <= 0
//   -> ndc = clip.xyz / w  ->  lens distortion as an NDC warp  ->  viewport to pixels in the origin's convention.
#pragma once

#include <optional>
#include <span>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "clip.h"
#include "distortion.h"
#include "geometry.h"
#include "lens.h"
#include "polylines.h"
#include "pose.h"
#include "projection.h"
#include "result.h"
#include "viewport.h"

namespace overlayd {

enum class PointStatus {
    Clipped, // behind the near plane, beyond the far plane, or outside the lens's valid field: no pixel
    Outside, // in front of the camera but outside the scissor rectangle
    Visible, // lands inside the scissor rectangle
};

struct ProjectedPoint {
    glm::dvec2 pixel{0.0}; // meaningful unless Clipped
    double depth = 0.0;    // NDC depth in the projection's DepthRange; meaningful unless Clipped
    PointStatus status = PointStatus::Clipped;
};

// Chord error allowed when a straight 3D segment is drawn through a distorting lens as a polyline.
inline constexpr double kDefaultCurveTolerancePx = 0.25;

class Camera
{
public:
    // view maps world to the internal camera frame (Pose::viewMatrix(), possibly times a scene-graph inverse).
    static Result<Camera> create(const glm::dmat4 &view, const Projection &projection, const Distortion &distortion,
                                 const Viewport &viewport);
    static Result<Camera> create(const Pose &pose, const Projection &projection, const Distortion &distortion,
                                 const Viewport &viewport);

    ProjectedPoint project(const glm::dvec3 &world) const { return project(glm::dvec4(world, 1.0)); }
    ProjectedPoint project(const glm::dvec4 &world) const;
    // Batch form: out.size() must be at least world.size(); allocates nothing.
    void projectPoints(std::span<const glm::dvec3> world, std::span<ProjectedPoint> out) const;

    // Appends the visible part of the straight 3D segment a-b as polylines (several where the lens's valid field
    // cuts it); curved through a distorting lens to within tolerancePx.
    void projectSegment(const glm::dvec4 &a, const glm::dvec4 &b, Polylines &out,
                        double tolerancePx = kDefaultCurveTolerancePx) const;
    // A connected 3D polyline (closed: last point joins the first); unbroken runs come out as one polyline.
    void projectPolyline(std::span<const glm::dvec4> world, bool closed, Polylines &out,
                         double tolerancePx = kDefaultCurveTolerancePx) const;

    // The world-space ray of points that land on `pixel` (origin convention). Perspective rays start at the
    // camera centre, orthographic rays on the near plane.
    Result<Ray> unproject(const glm::dvec2 &pixel) const;

    const glm::dmat4 &view() const { return view_; }
    const Projection &projection() const { return projection_; }
    const glm::dmat4 &viewProjection() const { return viewProjection_; }
    const Viewport &viewport() const { return viewport_; }
    const std::optional<Lens> &lens() const { return lens_; }
    const ClipPlanes &segmentClipPlanes() const { return segmentPlanes_; }
    glm::dvec3 position() const;

private:
    // Constants of the per-point path from clip space to pixels, composed once so that projectPoints runs a
    // short loop per lens model (see camera.cpp).
    struct PointPath {
        glm::dmat2 toNormalized{1.0};  // (clip.x, clip.y, clip.w) -> w * normalized optical coordinates
        glm::dvec2 toNormalizedW{0.0}; //   (for no lens: w * NDC)
        glm::dmat2 toPixel{1.0};       // (distorted) normalized coordinates or NDC -> pixel
        glm::dvec2 toPixelOffset{0.0};
        double validRadius2 = 0.0;
        double nearW = 0.0; // the near test is z + nearW * w >= 0: 0 for ZeroToOne, 1 for MinusOneToOne
        bool hasFar = false;
        glm::dvec2 scissorMin{0.0}, scissorMax{0.0};
    };
    // The pixel of a clip-space point known to be in front and inside the lens cone, and the whole per-point test
    // and mapping, for one lens model (DistortionModel::None: no lens).
    // Always inlined: the batch loop relies on it (an out-of-line call per point costs more than the maths).
    template<DistortionModel Model>
    [[gnu::always_inline]] static inline glm::dvec2
    pixelFromClip(const PointPath &path, const std::array<double, 8> &coeffs, const glm::dvec4 &clip, double inverseW);
    template<DistortionModel Model>
    [[gnu::always_inline]] static inline bool isClipped(const PointPath &path, const glm::dvec4 &clip);
    [[gnu::always_inline]] static inline void store(const PointPath &path, const glm::dvec2 &pixel, double depth,
                                                    ProjectedPoint &out);
    template<DistortionModel Model>
    [[gnu::always_inline]] static inline void projectClip(const PointPath &path, const std::array<double, 8> &coeffs,
                                                          const glm::dvec4 &clip, ProjectedPoint &out);
    template<DistortionModel Model>
    void projectBatch(std::span<const glm::dvec3> world, std::span<ProjectedPoint> out) const;

    Camera(const glm::dmat4 &view, const Projection &projection, std::optional<Lens> lens, const Viewport &viewport);
    PointPath composePointPath() const;

    // Pixel of a clip-space point already known to be clipped in (w > 0, inside the lens cone).
    glm::dvec2 clipToPixel(const glm::dvec4 &clip) const;
    void refine(const glm::dvec4 &a, const glm::dvec4 &d, double tA, const glm::dvec2 &pA, double tB,
                const glm::dvec2 &pB, int depth, double tolerance, Polylines &out) const;
    // Emits the clip-space piece a + t d, t in [t0, t1]; continues the last polyline when asked to.
    void emitPiece(const glm::dvec4 &a, const glm::dvec4 &d, double t0, double t1, bool continueLast, double tolerance,
                   Polylines &out) const;
    std::optional<std::array<double, 2>> clipSegment(const glm::dvec4 &a, const glm::dvec4 &b) const;

    glm::dmat4 view_;
    Projection projection_;
    std::optional<Lens> lens_;
    Viewport viewport_;
    glm::dmat4 viewProjection_;
    glm::dmat4 inverseViewProjection_;
    ClipPlanes segmentPlanes_;
    double nearPlaneW_; // the near test is z + nearPlaneW_ * w >= 0: 0 for ZeroToOne, 1 for MinusOneToOne
    PointPath path_;
};

} // namespace overlayd
