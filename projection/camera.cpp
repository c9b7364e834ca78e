// SPDX-License-Identifier: Apache-2.0
// Camera: projection of points and segments with clipping before the divide, lens curves, and unprojection.
#include "camera.h"

#include "camera_batch.h"
#include "point_kernel.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

namespace overlayd {

namespace {

// Side planes for lines of an undistorted camera: two window widths beyond each edge. Wide enough that a line's
// cap is never seen, narrow enough that pixel coordinates stay small for integer rasterizers.
constexpr NdcBounds kLineGuardBand{-3.0, 3.0, -3.0, 3.0};
// Subdivision limits for curved segments: at least 4 pieces are examined, at most 2^12.
constexpr int kMinRefineDepth = 2;
constexpr int kMaxRefineDepth = 12;
// chordError assumes each piece is a parabola; the cubic part it misses has been seen to add 0.2% (strong
// lenses, long pieces). Aiming 10% below the tolerance keeps the drawn polyline within it.
constexpr double kChordSafety = 0.9;

// The depth d of the near plane: the internal point (0, 0, -d) has clip z + nearW w = 0. For a perspective
// matrix w = d (m[2][3] = -1, m[3][3] = 0), so -m22 d + m32 + nearW d = 0.
double nearDistanceOf(const glm::dmat4 &m, double nearW)
{
    return m[3][2] / (m[2][2] - nearW);
}

// How far the curve strays from its chord AB, estimated from its point M at the parameter midpoint. Checking M's
// own distance is not enough: the parameter is not arc length (perspective and distortion stretch it), so M can
// sit well off the chord's middle where the curve is closer to the chord than elsewhere. Over a short piece a
// smooth curve is a parabola, whose offset at chord position s is 4 h s (1 - s) for a greatest offset h.
double chordError(const glm::dvec2 &m, const glm::dvec2 &a, const glm::dvec2 &b)
{
    const glm::dvec2 ab = b - a;
    const double length2 = glm::dot(ab, ab);
    if (!(length2 > 0.0))
        return glm::length(m - a);
    const double s = glm::dot(m - a, ab) / length2;
    const double offset = glm::length(m - (a + s * ab)); // from the line through A and B
    const double sc = std::clamp(s, 0.1, 0.9);           // M near an end: assume the worst of the middle range
    const double toSegment = glm::length(m - (a + std::clamp(s, 0.0, 1.0) * ab));
    return std::max(toSegment, offset / (4.0 * sc * (1.0 - sc)));
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
    // A finite value can still overflow here (a field of view of 1e-300 degrees: an infinite focal length).
    const glm::dmat4 &m = projection.matrix();
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r]))
                return makeError(ErrorCode::InvalidArgument,
                                 "the projection overflows (a field of view, focal length or size too small or large)");
    if (auto status = validateDistortion(distortion); !status)
        return status.error();
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

Camera::Camera(const glm::dmat4 &view, const Projection &projection, std::optional<Lens> lens, const Viewport &viewport)
    : view_(view), projection_(projection), lens_(std::move(lens)), viewport_(viewport),
      viewProjection_(projection.matrix() * view), inverseViewProjection_(glm::inverse(viewProjection_)),
      segmentPlanes_(projection.depthRange(), projection.hasFarPlane(), lens_ ? lens_->guardBand() : kLineGuardBand),
      nearPlaneW_(projection.depthRange() == DepthRange::MinusOneToOne ? 1.0 : 0.0),
      nearDistance_(nearDistanceOf(projection_.matrix(), nearPlaneW_)), path_(composePointPath()),
      wide_(composeWideField())
{}

WideField Camera::composeWideField() const
{
    WideField field;
    field.toNormalized = path_.toNormalized;
    field.toNormalizedW = path_.toNormalizedW;
    field.backSlope2 = path_.backSlope2;
    field.near2 = path_.near2;
    field.hasFar = path_.hasFar;
    return field;
}

PointPath Camera::composePointPath() const
{
    PointPath path;
    // The viewport is ndc * scale + offset in the user's origin; the camera works in memory order (one pixel
    // convention inside), so its mapping is the user's mirrored once here. Scale and offset are multiples of 0.5, so
    // both come out exact.
    const glm::dvec2 offset = viewport_.toTopLeft(viewport_.ndcToPixel(glm::dvec2(0.0)));
    const glm::dvec2 scale = viewport_.toTopLeft(viewport_.ndcToPixel(glm::dvec2(1.0))) - offset;
    const glm::dmat2 viewportLinear(scale.x, 0.0, 0.0, scale.y);
    if (lens_) {
        path.toNormalized = lens_->ndcToNormalized().linear;
        path.toNormalizedW = lens_->ndcToNormalized().offset;
        // Distorted normalized -> NDC -> pixel, as one affine map.
        path.toPixel = viewportLinear * lens_->normalizedToNdc().linear;
        path.toPixelOffset = scale * lens_->normalizedToNdc().offset + offset;
        path.validRadius2 = lens_->validRadius() * lens_->validRadius();
        path.coeffs = lens_->distortion().coeffs;
        if (lens_->seesBehind()) {
            const double backSlope = std::tan(M_PI - lens_->validAngle());
            path.wide = true;
            path.backSlope2 = backSlope * backSlope;
            path.near2 = nearDistance_ * nearDistance_;
        }
    } else {
        path.toPixel = viewportLinear;
        path.toPixelOffset = offset;
    }
    path.nearW = nearPlaneW_;
    path.hasFar = projection_.hasFarPlane();
    const PixelRect scissor = viewport_.scissorTopLeft();
    path.scissorMin = {scissor.x - 0.5, scissor.y - 0.5};
    path.scissorMax = {scissor.x + scissor.width - 0.5, scissor.y + scissor.height - 0.5};
    return path;
}

glm::dvec3 Camera::position() const
{
    const glm::dvec4 centre = glm::inverse(view_) * glm::dvec4(0, 0, 0, 1);
    return glm::dvec3(centre) / centre.w;
}

namespace {

using PointLanes = OVERLAYD_LANES_NS::ProjectedLanes<double>;

// The same kernel as the batch loops, on one point (see point_kernel.h), so both give the same bits.
PointLanes projectClip(const PointPath &path, DistortionModel model, const glm::dvec4 &clip)
{
    using OVERLAYD_LANES_NS::projectClipLanes;
    switch (model) {
    case DistortionModel::None:
        break;
    case DistortionModel::RadialTangential:
        return projectClipLanes<DistortionModel::RadialTangential>(path, clip.x, clip.y, clip.z, clip.w);
    case DistortionModel::Rational:
        return projectClipLanes<DistortionModel::Rational>(path, clip.x, clip.y, clip.z, clip.w);
    case DistortionModel::Fisheye:
        return projectClipLanes<DistortionModel::Fisheye>(path, clip.x, clip.y, clip.z, clip.w);
    }
    return projectClipLanes<DistortionModel::None>(path, clip.x, clip.y, clip.z, clip.w);
}

} // namespace

glm::dvec2 Camera::clipToPixel(const glm::dvec4 &clip) const
{
    const PointLanes r = projectClip(path_, lens_ ? lens_->distortion().model : DistortionModel::None, clip);
    return {r.x, r.y};
}

ProjectedPoint Camera::project(const glm::dvec4 &world) const
{
    const PointLanes r =
        projectClip(path_, lens_ ? lens_->distortion().model : DistortionModel::None, viewProjection_ * world);
    if (r.clipped)
        return ProjectedPoint{};
    return {{r.x, r.y}, r.depth, r.inScissor ? PointStatus::Visible : PointStatus::Outside};
}

SegmentPieces Camera::clipSegment(const glm::dvec4 &a, const glm::dvec4 &b) const
{
    if (path_.wide)
        return wide_.pieces(a, b);
    SegmentPieces pieces;
    auto range = segmentPlanes_.clipSegment(a, b);
    if (range && lens_)
        range = lens_->clipToValidCone(a, b, (*range)[0], (*range)[1]);
    if (range)
        pieces.ranges[pieces.count++] = *range;
    return pieces;
}

void Camera::refine(const glm::dvec4 &a, const glm::dvec4 &d, double tA, const glm::dvec2 &pA, double tB,
                    const glm::dvec2 &pB, int depth, double tolerance, Polylines &out) const
{
    const double tM = 0.5 * (tA + tB);
    const glm::dvec2 pM = clipToPixel(a + tM * d);
    const bool split = depth < kMinRefineDepth || chordError(pM, pA, pB) > kChordSafety * tolerance;
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
    const SegmentPieces pieces = clipSegment(ca, cb);
    for (int i = 0; i < pieces.count; ++i)
        emitPiece(ca, cb - ca, pieces.ranges[i][0], pieces.ranges[i][1], false, tolerancePx, out);
}

void Camera::projectPolyline(std::span<const glm::dvec4> world, bool closed, Polylines &out, double tolerancePx) const
{
    const std::size_t count = world.size();
    if (count < 2)
        return;
    const std::size_t segments = closed ? count : count - 1;
    bool previousReachedEnd = false;
    glm::dvec4 ca = viewProjection_ * world[0];
    for (std::size_t i = 0; i < segments; ++i) {
        const glm::dvec4 cb = viewProjection_ * world[(i + 1) % count];
        const SegmentPieces pieces = clipSegment(ca, cb);
        for (int p = 0; p < pieces.count; ++p) {
            const auto &range = pieces.ranges[p];
            const bool joins = previousReachedEnd && range[0] == 0.0;
            emitPiece(ca, cb - ca, range[0], range[1], joins, tolerancePx, out);
            previousReachedEnd = range[1] == 1.0;
        }
        if (pieces.count == 0)
            previousReachedEnd = false;
        ca = cb;
    }
}

Result<Ray> Camera::unproject(const glm::dvec2 &pixel) const
{
    glm::dvec2 ndc = viewport_.pixelToNdc(viewport_.toUser(pixel));
    if (path_.wide)
        return unprojectWide(ndc);
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

Result<Ray> Camera::unprojectWide(const glm::dvec2 &ndc) const
{
    // Distorted normalized point -> its angle theta_d and azimuth; theta from the model's inverse on the angle.
    const glm::dvec2 distorted = lens_->ndcToNormalized()(ndc);
    const double thetaD = glm::length(distorted);
    auto theta = undistortFisheyeAngle(lens_->distortion(), thetaD, lens_->validAngle());
    if (!theta)
        return theta.error();
    const glm::dvec2 azimuth = thetaD > 0.0 ? distorted / thetaD : glm::dvec2(0.0);
    const glm::dvec3 optical(std::sin(*theta) * azimuth, std::cos(*theta));
    // Optical <- internal camera frame, read off the projection matrix and the point path (columns: the images
    // of the internal axes), so no axis convention is assumed here.
    glm::dmat3 opticalFromInternal(0.0);
    for (int i = 0; i < 3; ++i) {
        glm::dvec4 axis(0.0);
        axis[i] = 1.0;
        opticalFromInternal[i] = wide_.optical(projection_.matrix() * axis);
    }
    const glm::dvec3 internal = glm::inverse(opticalFromInternal) * optical;
    const glm::dvec3 world = glm::dvec3(glm::inverse(view_) * glm::dvec4(internal, 0.0));
    return Ray{position(), glm::normalize(world)};
}

// A filled world polygon (a privacy mask) clipped in clip space, so that a polygon reaching behind the camera keeps
// the part in front instead of folding its hidden corners onto the image.
Status Camera::projectPolygon(std::span<const glm::dvec4> world, std::vector<glm::dvec2> &out, double tolerancePx) const
{
    out.clear();
    if (path_.wide)
        return makeError(ErrorCode::InvalidArgument,
                         "a world polygon cannot be projected through a lens that sees behind the camera");
    std::vector<glm::dvec4> clip, clipped;
    clip.reserve(world.size());
    for (const glm::dvec4 &p : world)
        clip.push_back(viewProjection_ * p);
    segmentPlanes_.clipPolygon(clip, clipped);
    Polylines outline;
    for (size_t i = 0; i < clipped.size(); ++i) {
        const glm::dvec4 &a = clipped[i], &b = clipped[(i + 1) % clipped.size()];
        emitPiece(a, b - a, 0.0, 1.0, true, tolerancePx, outline);
    }
    out = std::move(outline.points);
    return Ok{};
}

// The batch loops: one translation unit per instruction set (camera_batch*.cpp), chosen here at run time.
bool Camera::batchKernelAvailable(BatchKernel kernel)
{
    switch (kernel) {
    case BatchKernel::Best:
    case BatchKernel::Lanes2:
        return true;
#ifdef OVERLAYD_HAVE_X86_KERNELS
    // libgcc reads CPUID once at start-up; it also checks that the OS saves the AVX / AVX-512 registers.
    case BatchKernel::Lanes4Avx2:
        return __builtin_cpu_supports("avx2");
    case BatchKernel::Lanes8Avx512:
        return __builtin_cpu_supports("avx512f");
#else
    case BatchKernel::Lanes4Avx2:
    case BatchKernel::Lanes8Avx512:
        return false;
#endif
    }
    return false;
}

BatchKernel Camera::bestBatchKernel()
{
    return batchKernelAvailable(BatchKernel::Lanes8Avx512) ? BatchKernel::Lanes8Avx512
           : batchKernelAvailable(BatchKernel::Lanes4Avx2) ? BatchKernel::Lanes4Avx2
                                                           : BatchKernel::Lanes2;
}

void Camera::projectPoints(std::span<const glm::dvec3> world, std::span<ProjectedPoint> out, BatchKernel kernel) const
{
    const BatchJob job{path_,        viewProjection_, lens_ ? lens_->distortion().model : DistortionModel::None,
                       world.data(), out.data(),      std::min(world.size(), out.size())};
    if (kernel == BatchKernel::Best)
        kernel = bestBatchKernel();
    else if (!batchKernelAvailable(kernel))
        kernel = BatchKernel::Lanes2;
#ifdef OVERLAYD_HAVE_X86_KERNELS
    if (kernel == BatchKernel::Lanes8Avx512)
        return avx512::projectPoints(job);
    if (kernel == BatchKernel::Lanes4Avx2)
        return avx2::projectPoints(job);
#endif
    baseline::projectPoints(job);
}

} // namespace overlayd
