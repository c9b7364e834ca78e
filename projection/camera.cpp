// Camera: projection of points and segments with clipping before the divide, lens curves, and unprojection.
#include "camera.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

namespace overlayd {

namespace {

// Side planes for lines of an undistorted camera: two window widths beyond each edge. Wide enough that a line's
// cap is never seen, narrow enough that pixel coordinates stay small for integer rasterizers.
constexpr NdcBounds kLineGuardBand{-3.0, 3.0, -3.0, 3.0};
// Subdivision limits for curved segments: at least 4 pieces are examined, at most 2^12.
constexpr int kMinRefineDepth = 2;
constexpr int kMaxRefineDepth = 12;

double distanceToChord(const glm::dvec2 &p, const glm::dvec2 &a, const glm::dvec2 &b)
{
    const glm::dvec2 ab = b - a;
    const double length2 = glm::dot(ab, ab);
    const double t = length2 > 0.0 ? std::clamp(glm::dot(p - a, ab) / length2, 0.0, 1.0) : 0.0;
    return glm::length(p - (a + t * ab));
}

} // namespace

Result<Camera> Camera::create(const glm::dmat4 &view, const Projection &projection, const Distortion &distortion,
                              const Viewport &viewport)
{
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(view[c][r]))
                return makeError(ErrorCode::InvalidArgument, "view matrix must be finite");
    if (std::abs(glm::determinant(view)) < 1e-12)
        return makeError(ErrorCode::DegenerateBasis, "view matrix is singular");
    if (distortion.model == DistortionModel::None)
        return Camera(view, projection, std::nullopt, viewport);
    if (!projection.pinholeIntrinsics())
        return makeError(ErrorCode::Unsupported,
                         "lens distortion needs pinhole intrinsics (fx, fy, cx, cy); other projection forms "
                         "describe an ideal lens");
    auto lens = Lens::create(*projection.pinholeIntrinsics(), distortion);
    if (!lens)
        return lens.error();
    return Camera(view, projection, std::move(*lens), viewport);
}

Result<Camera> Camera::create(const Pose &pose, const Projection &projection, const Distortion &distortion,
                              const Viewport &viewport)
{
    return create(pose.viewMatrix(), projection, distortion, viewport);
}

Camera::Camera(const glm::dmat4 &view, const Projection &projection, std::optional<Lens> lens,
               const Viewport &viewport)
    : view_(view), projection_(projection), lens_(std::move(lens)), viewport_(viewport),
      viewProjection_(projection.matrix() * view), inverseViewProjection_(glm::inverse(viewProjection_)),
      segmentPlanes_(projection.depthRange(), projection.hasFarPlane(), lens_ ? lens_->guardBand() : kLineGuardBand),
      nearPlaneW_(projection.depthRange() == DepthRange::MinusOneToOne ? 1.0 : 0.0)
{
}

glm::dvec3 Camera::position() const
{
    const glm::dvec4 centre = glm::inverse(view_) * glm::dvec4(0, 0, 0, 1);
    return glm::dvec3(centre) / centre.w;
}

bool Camera::inFrontAndNearerThanFar(const glm::dvec4 &clip) const
{
    if (!(clip.w > 0.0) || clip.z + nearPlaneW_ * clip.w < 0.0)
        return false;
    if (projection_.hasFarPlane() && clip.w - clip.z < 0.0)
        return false;
    return !lens_ || lens_->insideValidCone(clip);
}

glm::dvec2 Camera::clipToPixel(const glm::dvec4 &clip) const
{
    const glm::dvec2 ndc = glm::dvec2(clip) / clip.w;
    return viewport_.ndcToPixel(lens_ ? lens_->distortNdc(ndc) : ndc);
}

ProjectedPoint Camera::project(const glm::dvec4 &world) const
{
    const glm::dvec4 clip = viewProjection_ * world;
    if (!inFrontAndNearerThanFar(clip))
        return {};
    const glm::dvec2 pixel = clipToPixel(clip);
    return {pixel, clip.z / clip.w, viewport_.inScissor(pixel) ? PointStatus::Visible : PointStatus::Outside};
}

void Camera::projectPoints(std::span<const glm::dvec3> world, std::span<ProjectedPoint> out) const
{
    const std::size_t n = std::min(world.size(), out.size());
    for (std::size_t i = 0; i < n; ++i)
        out[i] = project(glm::dvec4(world[i], 1.0));
}

std::optional<std::array<double, 2>> Camera::clipSegment(const glm::dvec4 &a, const glm::dvec4 &b) const
{
    auto range = segmentPlanes_.clipSegment(a, b);
    if (!range || !lens_)
        return range;
    return lens_->clipToValidCone(a, b, (*range)[0], (*range)[1]);
}

void Camera::refine(const glm::dvec4 &a, const glm::dvec4 &d, double tA, const glm::dvec2 &pA, double tB,
                    const glm::dvec2 &pB, int depth, double tolerance, Polylines &out) const
{
    const double tM = 0.5 * (tA + tB);
    const glm::dvec2 pM = clipToPixel(a + tM * d);
    const bool split = depth < kMinRefineDepth || distanceToChord(pM, pA, pB) > tolerance;
    if (split && depth < kMaxRefineDepth) {
        refine(a, d, tA, pA, tM, pM, depth + 1, tolerance, out);
        refine(a, d, tM, pM, tB, pB, depth + 1, tolerance, out);
    } else {
        out.extend(pB);
    }
}

void Camera::emitPiece(const glm::dvec4 &a, const glm::dvec4 &d, double t0, double t1, bool continueLast,
                       double tolerance, Polylines &out) const
{
    const glm::dvec2 p0 = clipToPixel(a + t0 * d);
    const glm::dvec2 p1 = clipToPixel(a + t1 * d);
    if (!continueLast || out.size() == 0)
        out.start(p0);
    if (!lens_) {
        out.extend(p1); // a pinhole without distortion keeps straight lines straight
        return;
    }
    refine(a, d, t0, p0, t1, p1, 0, tolerance, out);
}

void Camera::projectSegment(const glm::dvec4 &a, const glm::dvec4 &b, Polylines &out, double tolerancePx) const
{
    const glm::dvec4 ca = viewProjection_ * a, cb = viewProjection_ * b;
    if (auto range = clipSegment(ca, cb))
        emitPiece(ca, cb - ca, (*range)[0], (*range)[1], false, tolerancePx, out);
}

void Camera::projectPolyline(std::span<const glm::dvec4> world, bool closed, Polylines &out,
                             double tolerancePx) const
{
    const std::size_t count = world.size();
    if (count < 2)
        return;
    const std::size_t segments = closed ? count : count - 1;
    bool previousReachedEnd = false;
    glm::dvec4 ca = viewProjection_ * world[0];
    for (std::size_t i = 0; i < segments; ++i) {
        const glm::dvec4 cb = viewProjection_ * world[(i + 1) % count];
        auto range = clipSegment(ca, cb);
        if (range) {
            const bool joins = previousReachedEnd && (*range)[0] == 0.0;
            emitPiece(ca, cb - ca, (*range)[0], (*range)[1], joins, tolerancePx, out);
            previousReachedEnd = (*range)[1] == 1.0;
        } else {
            previousReachedEnd = false;
        }
        ca = cb;
    }
}

Result<Ray> Camera::unproject(const glm::dvec2 &pixel) const
{
    glm::dvec2 ndc = viewport_.pixelToNdc(pixel);
    if (lens_) {
        auto undistorted = lens_->undistortNdc(ndc);
        if (!undistorted)
            return undistorted.error();
        ndc = *undistorted;
    }
    // Two points on the ray: on the near plane and halfway through NDC depth (finite even for an infinite far).
    const double nearDepth = ndcNearDepth(projection_.depthRange());
    const glm::dvec4 h0 = inverseViewProjection_ * glm::dvec4(ndc, nearDepth, 1.0);
    const glm::dvec4 h1 = inverseViewProjection_ * glm::dvec4(ndc, 0.5 * (nearDepth + 1.0), 1.0);
    const glm::dvec3 p0 = glm::dvec3(h0) / h0.w, p1 = glm::dvec3(h1) / h1.w;
    if (projection_.isPerspective()) {
        const glm::dvec3 eye = position();
        return Ray{eye, glm::normalize(p0 - eye)};
    }
    return Ray{p0, glm::normalize(p1 - p0)};
}

} // namespace overlayd
