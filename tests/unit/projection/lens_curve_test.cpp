// SPDX-License-Identifier: Apache-2.0
// lens_curve_test: straight 3D segments drawn through distorting lenses follow OpenCV's curve within tolerance.
//
// The reference curve is OpenCV's projection (cv::projectPoints, cv::fisheye::projectPoints) of 2000 points of
// each segment; our polylines must pass within kDefaultCurveTolerancePx of every sample they are meant to cover.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <opencv2/calib3d.hpp>

#include "projection/camera.h"
#include "projection/opencv_reference.h"

namespace overlayd {
namespace {

using test::CvCamera;

constexpr int kSamples = 2000;
constexpr double kSlack = 1e-6;

double distanceToPolyline(const glm::dvec2 &p, std::span<const glm::dvec2> line)
{
    double best = glm::length(p - line[0]);
    for (std::size_t i = 1; i < line.size(); ++i) {
        const glm::dvec2 a = line[i - 1], ab = line[i] - a;
        const double length2 = glm::dot(ab, ab);
        const double t = length2 > 0.0 ? std::clamp(glm::dot(p - a, ab) / length2, 0.0, 1.0) : 0.0;
        best = std::min(best, glm::length(p - (a + t * ab)));
    }
    return best;
}

// A camera with distortion strong enough to bend lines by tens of pixels across the image.
CvCamera strongLens(DistortionModel model)
{
    CvCamera c;
    c.rvec = {0.2, -0.3, 0.1};
    c.tvec = {0.3, -0.5, 1.5};
    c.width = 1280;
    c.height = 960;
    c.fx = model == DistortionModel::Fisheye ? 350.0 : 700.0;
    c.fy = c.fx * 1.01;
    c.cx = 650.3;
    c.cy = 470.8;
    c.distortion.model = model;
    switch (model) {
    case DistortionModel::None:
        break;
    case DistortionModel::RadialTangential:
        c.distortion.coeffs = {-0.32, 0.11, 1.5e-3, -1e-3, -0.02};
        break;
    case DistortionModel::Rational:
        c.distortion.coeffs = {0.9, 0.3, 1e-3, 5e-4, 0.01, 1.2, 0.5, 0.05};
        break;
    case DistortionModel::Fisheye:
        c.distortion.coeffs = {0.08, -0.03, 0.01, -0.002};
        break;
    }
    return c;
}

// The parameter t in [0, 1] whose OpenCV pixel is nearest to `pixel`, and that distance: a dense scan, then a
// golden-section search in the best sample's neighbourhood.
std::pair<double, double> nearestOnCurve(const CvCamera &c, const glm::dvec3 &a, const glm::dvec3 &b,
                                         const std::vector<glm::dvec2> &samples, const glm::dvec2 &pixel)
{
    std::size_t best = 0;
    for (std::size_t i = 1; i < samples.size(); ++i)
        if (glm::length(samples[i] - pixel) < glm::length(samples[best] - pixel))
            best = i;
    const double step = 1.0 / (samples.size() - 1);
    double lo = std::max(0.0, (best - 1.0) * step), hi = std::min(1.0, (best + 1.0) * step);
    auto distance = [&](double t) {
        return glm::length(test::cvProject(c, a + t * (b - a)) - pixel);
    };
    const double g = (std::sqrt(5.0) - 1.0) / 2.0;
    for (int i = 0; i < 80; ++i) {
        const double m1 = hi - g * (hi - lo), m2 = lo + g * (hi - lo);
        if (distance(m1) < distance(m2))
            hi = m2;
        else
            lo = m1;
    }
    const double t = 0.5 * (lo + hi);
    return {t, distance(t)};
}

class LensCurve : public ::testing::TestWithParam<DistortionModel>
{};

TEST_P(LensCurve, PolylinesFollowOpenCvCurveWithinTolerance)
{
    const DistortionModel model = GetParam();
    const CvCamera c = strongLens(model);
    const Camera camera = test::makeCamera(c, DepthRange::ZeroToOne);
    ASSERT_TRUE(camera.lens());
    const NdcBounds guard = camera.lens()->guardBand();
    const double radius = test::testFieldRadius(camera);
    std::mt19937_64 rng(23 + static_cast<int>(model));
    std::size_t curvedPieces = 0, maxPoints = 0, coveredSamples = 0;
    double worst = 0.0;
    for (int s = 0; s < 150; ++s) {
        // Both ends in front and inside the valid cone; the cone is convex, so the whole segment is too.
        const glm::dvec3 oa = test::randomOpticalPoint(rng, radius, 0.5, 20.0);
        const glm::dvec3 ob = test::randomOpticalPoint(rng, radius, 0.5, 20.0);
        const glm::dvec3 a = test::worldFromOptical(c, oa), b = test::worldFromOptical(c, ob);
        Polylines out;
        camera.projectSegment(glm::dvec4(a, 1.0), glm::dvec4(b, 1.0), out);

        std::vector<glm::dvec3> world(kSamples);
        std::vector<bool> covered(kSamples);
        for (int i = 0; i < kSamples; ++i) {
            const double t = double(i) / (kSamples - 1);
            world[i] = a + t * (b - a);
            // Which samples the drawing must cover: those whose ideal-pinhole NDC lies inside the guard band
            // (the lens's side clip planes), with a margin for the rounding at the band's edge.
            const glm::dvec3 o = oa + t * (ob - oa);
            const double ndcX = 2.0 * (c.fx * o.x / o.z + c.cx + 0.5) / c.width - 1.0;
            const double ndcY = 1.0 - 2.0 * (c.fy * o.y / o.z + c.cy + 0.5) / c.height;
            const double margin = 1e-6;
            covered[i] = ndcX > guard.xMin + margin && ndcX < guard.xMax - margin && ndcY > guard.yMin + margin &&
                         ndcY < guard.yMax - margin;
        }
        const std::vector<glm::dvec2> reference = test::cvProject(c, world);
        const bool anyCovered = std::find(covered.begin(), covered.end(), true) != covered.end();
        if (!anyCovered)
            continue;
        // The guard band and the valid cone are convex: what is left of a segment is one piece.
        ASSERT_EQ(out.size(), 1u) << "segment " << s;
        const std::span<const glm::dvec2> line = out[0];
        maxPoints = std::max(maxPoints, line.size());
        curvedPieces += line.size() > 2;
        for (int i = 0; i < kSamples; ++i) {
            if (!covered[i])
                continue;
            ++coveredSamples;
            const double d = distanceToPolyline(reference[i], line);
            worst = std::max(worst, d);
            ASSERT_LE(d, kDefaultCurveTolerancePx + kSlack)
                << test::modelName(model) << " segment " << s << " sample " << i << " of " << kSamples
                << " is off the drawn polyline (" << line.size() << " points)" << [&] {
                       std::string text;
                       for (const glm::dvec2 &v : line)
                           text += " (" + std::to_string(v.x) + ", " + std::to_string(v.y) + ")";
                       return text + " sample (" + std::to_string(reference[i].x) + ", " +
                              std::to_string(reference[i].y) + ")";
                   }();
        }
        // The polyline's ends are points of the true curve, not merely near it.
        for (const glm::dvec2 &end : {line.front(), line.back()}) {
            const auto [t, distance] = nearestOnCurve(c, a, b, reference, end);
            EXPECT_LE(distance, 1e-6) << test::modelName(model) << " segment " << s << " end at t " << t;
        }
        // And every vertex too: the polyline interpolates the curve.
        for (const glm::dvec2 &vertex : line)
            EXPECT_LE(distanceToPolyline(vertex, reference), 0.05) << "segment " << s;
    }
    RecordProperty("worst_px", std::to_string(worst));
    EXPECT_GT(coveredSamples, 30000u);
    EXPECT_GT(curvedPieces, 50u) << "the lens should bend most segments";
    EXPECT_GT(maxPoints, 8u);
}

// A tighter tolerance gives more points and still holds; a looser one fewer.
TEST_P(LensCurve, ToleranceIsHonouredAtOtherValues)
{
    const DistortionModel model = GetParam();
    const CvCamera c = strongLens(model);
    const Camera camera = test::makeCamera(c, DepthRange::MinusOneToOne);
    const double radius = std::min(test::testFieldRadius(camera), 0.8);
    std::mt19937_64 rng(29);
    for (int s = 0; s < 40; ++s) {
        const glm::dvec3 a = test::worldFromOptical(c, test::randomOpticalPoint(rng, radius, 1.0, 10.0));
        const glm::dvec3 b = test::worldFromOptical(c, test::randomOpticalPoint(rng, radius, 1.0, 10.0));
        std::vector<glm::dvec3> world(kSamples);
        for (int i = 0; i < kSamples; ++i)
            world[i] = a + (double(i) / (kSamples - 1)) * (b - a);
        const std::vector<glm::dvec2> reference = test::cvProject(c, world);
        std::size_t previous = 0;
        for (const double tolerance : {2.0, 0.25, 0.02}) {
            Polylines out;
            camera.projectSegment(glm::dvec4(a, 1.0), glm::dvec4(b, 1.0), out, tolerance);
            ASSERT_EQ(out.size(), 1u);
            for (int i = 0; i < kSamples; ++i)
                ASSERT_LE(distanceToPolyline(reference[i], out[0]), tolerance + kSlack)
                    << "segment " << s << " tolerance " << tolerance;
            EXPECT_GE(out[0].size(), previous);
            previous = out[0].size();
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Models, LensCurve,
                         ::testing::Values(DistortionModel::RadialTangential, DistortionModel::Rational,
                                           DistortionModel::Fisheye),
                         [](const auto &param) { return std::string(test::modelName(param.param)); });

// Without distortion straight lines stay straight: exactly two points per visible segment, at OpenCV's pixels
// when the ends are inside the view.
TEST(LensCurveNoDistortion, SegmentIsExactlyTwoPoints)
{
    CvCamera c = strongLens(DistortionModel::None);
    const Camera camera = test::makeCamera(c, DepthRange::ZeroToOne);
    std::mt19937_64 rng(31);
    int drawn = 0;
    for (int s = 0; s < 500; ++s) {
        const glm::dvec3 a = test::worldFromOptical(c, test::randomOpticalPoint(rng, 0.8, 0.5, 20.0));
        const glm::dvec3 b = test::worldFromOptical(c, test::randomOpticalPoint(rng, 0.8, 0.5, 20.0));
        Polylines out;
        camera.projectSegment(glm::dvec4(a, 1.0), glm::dvec4(b, 1.0), out);
        ASSERT_EQ(out.size(), 1u);
        ASSERT_EQ(out[0].size(), 2u);
        EXPECT_LE(glm::length(out[0][0] - test::cvProject(c, a)), 1e-6);
        EXPECT_LE(glm::length(out[0][1] - test::cvProject(c, b)), 1e-6);
        ++drawn;
    }
    EXPECT_EQ(drawn, 500);
}

// k1 = -0.5 alone: the radial map r (1 - r^2 / 2) peaks at r* = sqrt(2/3) and folds back towards the centre
// beyond it. The image here reaches r = 1.6, so OpenCV maps points far outside the calibrated field onto it.
class FoldingLens : public ::testing::Test
{
protected:
    FoldingLens() : c(makeCv()), camera(test::makeCamera(c, DepthRange::ZeroToOne)) {}

    static CvCamera makeCv()
    {
        CvCamera cv;
        cv.rvec = {0.0, 0.0, 0.0};
        cv.tvec = {0.0, 0.0, 0.0};
        cv.width = 1280;
        cv.height = 960;
        cv.fx = cv.fy = 400.0;
        cv.cx = 639.5;
        cv.cy = 479.5;
        cv.distortion = {DistortionModel::RadialTangential, {-0.5, 0, 0, 0, 0, 0, 0, 0}};
        return cv;
    }

    const double foldRadius = std::sqrt(2.0 / 3.0);
    CvCamera c;
    Camera camera;
};

TEST_F(FoldingLens, ValidRadiusStopsAtTheFold)
{
    ASSERT_TRUE(camera.lens());
    EXPECT_LE(camera.lens()->validRadius(), foldRadius) << "the folded part must never count as valid";
    EXPECT_GE(camera.lens()->validRadius(), foldRadius * (1.0 - 1e-3)) << "and the valid field must not shrink";
}

TEST_F(FoldingLens, PointsBeyondTheFoldAreClippedThoughOpenCvPutsThemInTheImage)
{
    const double valid = camera.lens()->validRadius();
    int folded = 0;
    for (int i = 0; i <= 200; ++i) {
        const double r = 0.05 + 1.5 * i / 200.0, phi = 0.7 * i;
        const glm::dvec3 p(r * std::cos(phi) * 3.0, r * std::sin(phi) * 3.0, 3.0); // world = optical here
        const ProjectedPoint ours = camera.project(p);
        const glm::dvec2 theirs = test::cvProject(c, p);
        const glm::dvec4 clip = camera.viewProjection() * glm::dvec4(p, 1.0);
        if (r > foldRadius * 1.001) {
            EXPECT_EQ(ours.status, PointStatus::Clipped) << "r " << r;
            EXPECT_FALSE(camera.lens()->insideValidCone(clip)) << "r " << r;
            if (r < 1.41) { // beyond that the fold crosses the centre and goes on outwards mirrored
                EXPECT_TRUE(theirs.x >= 0 && theirs.x < c.width && theirs.y >= 0 && theirs.y < c.height)
                    << "OpenCV draws the folded point at r " << r << " inside the image";
                ++folded;
            }
        } else if (r < valid) {
            ASSERT_NE(ours.status, PointStatus::Clipped) << "r " << r;
            EXPECT_TRUE(camera.lens()->insideValidCone(clip));
            EXPECT_LE(glm::length(ours.pixel - theirs), 1e-6);
        }
    }
    EXPECT_GT(folded, 50);
}

TEST_F(FoldingLens, SegmentsStopAtTheFold)
{
    // A horizontal segment at normalized y = 0.1 across the whole field, x from -1.3 to 1.3, at depth 2.
    const double y = 0.1, depth = 2.0;
    const glm::dvec3 a(-1.3 * depth, y * depth, depth), b(1.3 * depth, y * depth, depth);
    Polylines out;
    camera.projectSegment(glm::dvec4(a, 1.0), glm::dvec4(b, 1.0), out);
    ASSERT_EQ(out.size(), 1u);
    const std::span<const glm::dvec2> line = out[0];

    // The valid part is |x| <= sqrt(r*^2 - y^2); its ends are where the folded image turns back.
    const double xMax = std::sqrt(foldRadius * foldRadius - y * y);
    std::vector<glm::dvec3> valid;
    for (int i = 0; i < kSamples; ++i)
        valid.push_back({(-xMax + 2.0 * xMax * i / (kSamples - 1)) * depth, y * depth, depth});
    const std::vector<glm::dvec2> curve = test::cvProject(c, valid);
    // At the fold the image is stationary in r, so the ends agree closely even though validRadius is a scan.
    EXPECT_LE(glm::length(line.front() - curve.front()), 0.01);
    EXPECT_LE(glm::length(line.back() - curve.back()), 0.01);
    for (const glm::dvec2 &vertex : line)
        EXPECT_LE(distanceToPolyline(vertex, curve), kDefaultCurveTolerancePx + kSlack);
    for (const glm::dvec2 &sample : curve)
        EXPECT_LE(distanceToPolyline(sample, line), kDefaultCurveTolerancePx + 0.01);
    // Drawing the folded parts would retrace the curve backwards and double the length.
    auto length = [](std::span<const glm::dvec2> l) {
        double sum = 0.0;
        for (std::size_t i = 1; i < l.size(); ++i)
            sum += glm::length(l[i] - l[i - 1]);
        return sum;
    };
    EXPECT_NEAR(length(line), length(curve), 0.01 * length(curve));

    // A segment wholly in the folded region draws nothing.
    Polylines folded;
    camera.projectSegment(glm::dvec4(1.0 * depth, y * depth, depth, 1.0),
                          glm::dvec4(1.3 * depth, y * depth, depth, 1.0), folded);
    EXPECT_EQ(folded.points.size(), 0u);
}

} // namespace
} // namespace overlayd
