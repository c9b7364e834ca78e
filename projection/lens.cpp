// SPDX-License-Identifier: Apache-2.0
// Lens: distortion in normalized optical coordinates, wrapped so that callers work in NDC.
#include "lens.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace overlayd {

Result<Lens> Lens::create(const PinholeIntrinsics &k, const Distortion &distortion)
{
    if (auto status = validateDistortion(distortion); !status)
        return status.error();
    Lens lens;
    lens.distortion_ = distortion;
    // Pixel (u, v) from NDC: u = (x + 1) W / 2 - 0.5, v = (1 - y) H / 2 - 0.5 (top-left, centres at integers).
    const Affine2 ndcToPixel{glm::dmat2(k.width / 2.0, 0.0, 0.0, -k.height / 2.0),
                             glm::dvec2(k.width / 2.0 - 0.5, k.height / 2.0 - 0.5)};
    // Normalized (x, y) from pixel: the inverse of u = fx x + skew y + cx, v = fy y + cy.
    const glm::dmat2 kLinear(k.fx, 0.0, k.skew, k.fy);
    const Affine2 normalizedToPixel{kLinear, glm::dvec2(k.cx, k.cy)};
    const glm::dmat2 kInverse = glm::inverse(kLinear);
    const Affine2 pixelToNormalized{kInverse, -(kInverse * glm::dvec2(k.cx, k.cy))};
    const glm::dmat2 pixelToNdcLinear = glm::inverse(ndcToPixel.linear);
    const Affine2 pixelToNdc{pixelToNdcLinear, -(pixelToNdcLinear * ndcToPixel.offset)};
    lens.ndcToNormalized_ = ndcToPixel.then(pixelToNormalized);
    lens.normalizedToNdc_ = normalizedToPixel.then(pixelToNdc);
    lens.validRadius_ = monotonicRadius(distortion);
    lens.validAngle_ =
        distortion.model == DistortionModel::Fisheye ? fisheyeFieldAngle(distortion) : std::atan(lens.validRadius_);
    lens.guardBand_ = lens.computeGuardBand();
    return lens;
}

glm::dvec2 Lens::distortNdc(const glm::dvec2 &ndc) const
{
    return normalizedToNdc_(distortNormalized(distortion_, ndcToNormalized_(ndc)));
}

Result<glm::dvec2> Lens::undistortNdc(const glm::dvec2 &distortedNdc) const
{
    auto undistorted = undistortNormalized(distortion_, ndcToNormalized_(distortedNdc));
    if (!undistorted)
        return undistorted.error();
    if (glm::length(*undistorted) > validRadius_)
        return makeError(ErrorCode::NoConvergence, "pixel lies outside the lens model's valid field");
    return normalizedToNdc_(*undistorted);
}

bool Lens::insideValidCone(const glm::dvec4 &clip) const
{
    // normalized * w = linear * clip.xy + offset * w is linear in the clip-space point.
    const glm::dvec2 scaled = ndcToNormalized_.linear * glm::dvec2(clip) + ndcToNormalized_.offset * clip.w;
    return glm::dot(scaled, scaled) <= validRadius_ * validRadius_ * clip.w * clip.w;
}

std::optional<std::array<double, 2>> Lens::clipToValidCone(const glm::dvec4 &a, const glm::dvec4 &b, double t0,
                                                           double t1) const
{
    // Along the segment, q(t) = |L0 + t L1|^2 - r^2 (w0 + t w1)^2 <= 0 on one interval (the cone is convex).
    const glm::dvec4 d = b - a;
    const glm::dvec2 l0 = ndcToNormalized_.linear * glm::dvec2(a) + ndcToNormalized_.offset * a.w;
    const glm::dvec2 l1 = ndcToNormalized_.linear * glm::dvec2(d) + ndcToNormalized_.offset * d.w;
    const double r2 = validRadius_ * validRadius_;
    const double qa = glm::dot(l1, l1) - r2 * d.w * d.w;
    const double qb = 2.0 * (glm::dot(l0, l1) - r2 * a.w * d.w);
    const double qc = glm::dot(l0, l0) - r2 * a.w * a.w;
    auto q = [&](double t) {
        return (qa * t + qb) * t + qc;
    };
    const double disc = qb * qb - 4.0 * qa * qc;
    if (std::abs(qa) < 1e-300) { // linear
        if (std::abs(qb) < 1e-300)
            return qc <= 0.0 ? std::optional(std::array{t0, t1}) : std::nullopt;
        const double root = -qc / qb;
        if (qb > 0.0)
            t1 = std::min(t1, root);
        else
            t0 = std::max(t0, root);
    } else if (disc < 0.0) {
        if (q(0.5 * (t0 + t1)) > 0.0)
            return std::nullopt;
    } else {
        const double s = std::sqrt(disc);
        // Numerically stable roots.
        const double k = -0.5 * (qb + std::copysign(s, qb));
        double r1 = k / qa, r2root = k != 0.0 ? qc / k : r1;
        if (r1 > r2root)
            std::swap(r1, r2root);
        if (qa > 0.0) { // inside between the roots
            t0 = std::max(t0, r1);
            t1 = std::min(t1, r2root);
        } else {
            // Inside beyond either root; with w > 0 on all of [t0, t1] only one of the two rays can meet it.
            if (t0 <= std::min(t1, r1))
                t1 = std::min(t1, r1);
            else
                t0 = std::max(t0, r2root);
        }
    }
    if (t0 > t1)
        return std::nullopt;
    return std::array{t0, t1};
}

NdcBounds Lens::computeGuardBand() const
{
    // Walk the image border in distorted NDC, undistort each point (capped at the valid radius) and take the box.
    constexpr int kSamples = 64;
    NdcBounds box{1e300, -1e300, 1e300, -1e300};
    auto include = [&](const glm::dvec2 &distorted) {
        glm::dvec2 n = ndcToNormalized_(distorted);
        if (auto u = undistortNormalized(distortion_, n); u && glm::length(*u) <= validRadius_)
            n = *u;
        else if (std::isfinite(validRadius_))
            n = glm::normalize(n) * validRadius_;
        else
            return; // a lens that sees behind the camera clips segments on the angle, not with side planes
        const glm::dvec2 ndc = normalizedToNdc_(n);
        box = {std::min(box.xMin, ndc.x), std::max(box.xMax, ndc.x), std::min(box.yMin, ndc.y),
               std::max(box.yMax, ndc.y)};
    };
    for (int i = 0; i <= kSamples; ++i) {
        const double s = -1.0 + 2.0 * i / kSamples;
        include({s, -1.0});
        include({s, 1.0});
        include({-1.0, s});
        include({1.0, s});
    }
    const double mx = 0.05 * (box.xMax - box.xMin), my = 0.05 * (box.yMax - box.yMin);
    return {box.xMin - mx, box.xMax + mx, box.yMin - my, box.yMax + my};
}

} // namespace overlayd
