// SPDX-License-Identifier: Apache-2.0
// A calibrated lens: pinhole intrinsics plus distortion, applied as a warp of NDC (so any viewport can follow).
#pragma once

#include <cmath>

#include <glm/mat2x2.hpp>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "base/result.h"
#include "clip.h"
#include "distortion.h"
#include "projection.h"

namespace overlayd {

// A 2D affine map y = linear * x + offset.
struct Affine2 {
    glm::dmat2 linear{1.0};
    glm::dvec2 offset{0.0};
    glm::dvec2 operator()(const glm::dvec2 &x) const { return linear * x + offset; }
    Affine2 then(const Affine2 &next) const { return {next.linear * linear, next.linear * offset + next.offset}; }
};

class Lens
{
public:
    static Result<Lens> create(const PinholeIntrinsics &k, const Distortion &distortion);

    // Undistorted NDC (what the pinhole matrix produces) <-> normalized optical coordinates (X/Z, Y/Z).
    const Affine2 &ndcToNormalized() const { return ndcToNormalized_; }
    const Affine2 &normalizedToNdc() const { return normalizedToNdc_; }
    glm::dvec2 distortNdc(const glm::dvec2 &ndc) const;
    Result<glm::dvec2> undistortNdc(const glm::dvec2 &distortedNdc) const;

    const Distortion &distortion() const { return distortion_; }
    // Normalized radius beyond which the model folds back (see monotonicRadius); nothing past it is drawn.
    double validRadius() const { return validRadius_; }
    // The angle from the optical axis up to which the model is valid (atan(validRadius) but for a wide fisheye).
    double validAngle() const { return validAngle_; }
    // A fisheye declared wider than 180 degrees whose model keeps growing past 90: it sees points behind the
    // camera plane, which no X/Z radius describes (validRadius is then infinite and the camera works on the angle).
    bool seesBehind() const { return validAngle_ > M_PI / 2; }
    // Whether a clip-space point lies inside the cone of valid radii (w > 0 assumed).
    bool insideValidCone(const glm::dvec4 &clip) const;
    // The part [t0, t1] of the clip-space segment a + t (b - a) inside the valid cone, within [t0, t1] given.
    std::optional<std::array<double, 2>> clipToValidCone(const glm::dvec4 &a, const glm::dvec4 &b, double t0,
                                                         double t1) const;
    // NDC bounds of the undistorted region the image shows, with a margin: the side clip planes for lines.
    const NdcBounds &guardBand() const { return guardBand_; }

private:
    Lens() = default;
    NdcBounds computeGuardBand() const;

    Distortion distortion_;
    Affine2 ndcToNormalized_;
    Affine2 normalizedToNdc_;
    double validRadius_ = 0.0;
    double validAngle_ = 0.0;
    NdcBounds guardBand_;
};

} // namespace overlayd
