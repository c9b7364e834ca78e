// SPDX-License-Identifier: Apache-2.0
// The camera: pose, projection, optional lens and viewport, composed once; projects, clips and unprojects.
//
// The pipeline for a world point X (homogeneous, so directions at infinity project too):
//   clip = P * V * X  ->  clip against near/far (and side/lens planes for lines), never dividing by w <= 0
//   -> ndc = clip.xyz / w  ->  lens distortion as an NDC warp  ->  viewport to pixels, in memory order (row 0 at
//   the top) whatever the viewport's origin: the one pixel convention inside; Viewport::toUser is the way out.
#pragma once

#include <optional>
#include <span>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "base/result.h"
#include "clip.h"
#include "distortion.h"
#include "geometry.h"
#include "lens.h"
#include "point_path.h"
#include "polylines.h"
#include "pose.h"
#include "projection.h"
#include "viewport.h"
#include "wide_field.h"

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

// The batch loops of Camera::projectPoints: all give the same bits; Best is the widest this CPU runs.
enum class BatchKernel {
    Best,
    Lanes2,       // SSE2 (any x86-64) or NEON (arm64)
    Lanes4Avx2,   // x86-64 with AVX2
    Lanes8Avx512, // x86-64 with AVX-512F
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
    // Batch form: projects min(world.size(), out.size()) points; allocates nothing. Same bits as project(), in
    // registers of 2, 4 or 8 points, two or four registers interleaved (the widest loop the CPU runs; see
    // docs/speed.md).
    void projectPoints(std::span<const glm::dvec3> world, std::span<ProjectedPoint> out) const
    {
        projectPoints(world, out, BatchKernel::Best);
    }
    // The same with a chosen loop, for tests and benchmarks; a kernel this CPU cannot run falls back to Lanes2.
    void projectPoints(std::span<const glm::dvec3> world, std::span<ProjectedPoint> out, BatchKernel kernel) const;
    // Whether this build and this CPU can run `kernel` (Best and Lanes2 always can).
    static bool batchKernelAvailable(BatchKernel kernel);
    // The loop Best stands for on this CPU (never Best itself).
    static BatchKernel bestBatchKernel();

    // Appends the visible part of the straight 3D segment a-b as polylines (several where the lens's valid field
    // cuts it); curved through a distorting lens to within tolerancePx.
    void projectSegment(const glm::dvec4 &a, const glm::dvec4 &b, Polylines &out,
                        double tolerancePx = kDefaultCurveTolerancePx) const;
    // A connected 3D polyline (closed: last point joins the first); unbroken runs come out as one polyline.
    void projectPolyline(std::span<const glm::dvec4> world, bool closed, Polylines &out,
                         double tolerancePx = kDefaultCurveTolerancePx) const;

    // The visible part of a flat, closed 3D polygon as a pixel outline (memory order; empty when nothing is seen):
    // clipped against the near, far and guard-band side planes before the divide, each edge curved through the lens
    // to within tolerancePx. A lens that sees behind the camera has no such clip: refused.
    Status projectPolygon(std::span<const glm::dvec4> world, std::vector<glm::dvec2> &out,
                          double tolerancePx = kDefaultCurveTolerancePx) const;

    // The world-space ray of points that land on `pixel` (memory order). Perspective rays start at the
    // camera centre, orthographic rays on the near plane.
    Result<Ray> unproject(const glm::dvec2 &pixel) const;

    const glm::dmat4 &view() const { return view_; }
    const Projection &projection() const { return projection_; }
    const glm::dmat4 &viewProjection() const { return viewProjection_; }
    const Viewport &viewport() const { return viewport_; }
    const std::optional<Lens> &lens() const { return lens_; }
    const ClipPlanes &segmentClipPlanes() const { return segmentPlanes_; }
    glm::dvec3 position() const;
    // The near distance along the optical axis (a pinhole projection's near plane, in metres).
    double nearDistance() const { return nearDistance_; }
    // A fisheye of more than 180 degrees: it sees behind the camera plane, and clips by the near sphere
    // |P| < near instead of the near plane (docs/config.md, "Fisheye lenses beyond 180 degrees").
    bool seesBehind() const { return lens_ && lens_->seesBehind(); }

private:
    Camera(const glm::dmat4 &view, const Projection &projection, std::optional<Lens> lens, const Viewport &viewport);
    PointPath composePointPath() const;

    // Pixel of a clip-space point already known to be clipped in (w > 0, inside the lens cone).
    glm::dvec2 clipToPixel(const glm::dvec4 &clip) const;
    void refine(const glm::dvec4 &a, const glm::dvec4 &d, double tA, const glm::dvec2 &pA, double tB,
                const glm::dvec2 &pB, int depth, double tolerance, Polylines &out) const;
    // Emits the clip-space piece a + t d, t in [t0, t1]; continues the last polyline when asked to.
    void emitPiece(const glm::dvec4 &a, const glm::dvec4 &d, double t0, double t1, bool continueLast, double tolerance,
                   Polylines &out) const;
    SegmentPieces clipSegment(const glm::dvec4 &a, const glm::dvec4 &b) const;
    WideField composeWideField() const;
    // Through a lens that sees behind the camera the optical direction is no NDC point: the angle path.
    Result<Ray> unprojectWide(const glm::dvec2 &ndc) const;

    glm::dmat4 view_;
    Projection projection_;
    std::optional<Lens> lens_;
    Viewport viewport_;
    glm::dmat4 viewProjection_;
    glm::dmat4 inverseViewProjection_;
    ClipPlanes segmentPlanes_;
    double nearPlaneW_; // the near test is z + nearPlaneW_ * w >= 0: 0 for ZeroToOne, 1 for MinusOneToOne
    double nearDistance_;
    PointPath path_;
    WideField wide_;
};

} // namespace overlayd
