// SPDX-License-Identifier: Apache-2.0
// StrokeRasterizer against independent references: OpenCV's non-anti-aliased fills at 16x resolution averaged down
// (the exact covered area), cv::pointPolygonTest for pixel centres, and hand-computed widths and end positions.
#include "overlay/raster/stroke_raster.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

namespace overlayd {
namespace {

using Line = std::vector<glm::dvec2>;

// Paints every row() into a canvas of sink pixels and records each broken promise of the CoverageSink contract.
class RecordingSink final : public CoverageSink
{
public:
    RecordingSink(int width, int height, const LayerRect &clip)
        : canvas(cv::Mat::zeros(height, width, CV_8UC1)), clip_(clip)
    {}
    void begin(Rgba) override {}
    void end() override {}
    void row(int y, int x0, const uint8_t *coverage, int count) override
    {
        ++calls;
        pixels += count;
        if (count <= 0 || coverage[0] == 0 || coverage[count - 1] == 0)
            problems.push_back("untrimmed or empty call at row " + std::to_string(y));
        if (y < clip_.y0 || y >= clip_.y1 || x0 < clip_.x0 || x0 + count > clip_.x1)
            problems.push_back("outside the clip at row " + std::to_string(y) + " x " + std::to_string(x0));
        else if (y < lastY_ || (y == lastY_ && x0 < lastX1_))
            problems.push_back("out of order or overlapping at row " + std::to_string(y));
        lastY_ = y, lastX1_ = x0 + count;
        for (int i = 0; i < count; ++i)
            if (y >= 0 && y < canvas.rows && x0 + i >= 0 && x0 + i < canvas.cols)
                canvas.at<uint8_t>(y, x0 + i) = coverage[i];
    }

    cv::Mat canvas;
    std::vector<std::string> problems;
    long calls = 0, pixels = 0;

private:
    LayerRect clip_;
    int lastY_ = std::numeric_limits<int>::min(), lastX1_ = 0;
};

Polylines polylines(const std::vector<Line> &lines)
{
    Polylines out;
    for (const Line &line : lines) {
        out.start(line.front());
        for (size_t i = 1; i < line.size(); ++i)
            out.extend(line[i]);
    }
    return out;
}

cv::Mat rasterize(const std::vector<Line> &lines, double width, bool antialias, cv::Size size,
                  glm::dvec2 origin = {0, 0}, LayerRect clip = {})
{
    if (clip.empty())
        clip = {0, 0, size.width, size.height};
    RecordingSink sink(size.width, size.height, clip);
    StrokeRasterizer raster;
    raster.rasterize(polylines(lines), width, antialias, origin, clip, sink);
    EXPECT_TRUE(sink.problems.empty()) << sink.problems.front();
    return sink.canvas;
}

// The exact covered area of each pixel (0..255, float): the stroke's quads (butt ends) and interior joints' discs
// filled without anti-aliasing at 16x (fine pixel centres at 16 x + 7.5), then averaged per pixel. OpenCV's fills
// include both end pixels of every span, which grows a shape by about half a fine pixel on every side (measured:
// the count exceeds the area by half the perimeter, at every angle; a filled circle's radius by 0.3-0.5): every
// edge is moved in by half a fine pixel to cancel it.
cv::Mat areaReference(const std::vector<Line> &lines, double width, cv::Size size)
{
    constexpr int kScale = 16, kBits = 4;
    constexpr double kInset = 0.5 / kScale;
    cv::Mat fine = cv::Mat::zeros(size.height * kScale, size.width * kScale, CV_8UC1);
    const auto fixed = [](glm::dvec2 p) {
        return cv::Point(int(std::lround((kScale * p.x + 7.5) * (1 << kBits))),
                         int(std::lround((kScale * p.y + 7.5) * (1 << kBits))));
    };
    const double hw = width / 2 - kInset;
    for (const Line &line : lines) {
        for (size_t i = 0; i + 1 < line.size(); ++i) {
            const glm::dvec2 d = (line[i + 1] - line[i]) / glm::distance(line[i], line[i + 1]);
            const glm::dvec2 a = line[i] + kInset * d, b = line[i + 1] - kInset * d, n(-d.y * hw, d.x * hw);
            const cv::Point quad[4] = {fixed(a + n), fixed(b + n), fixed(b - n), fixed(a - n)};
            cv::fillConvexPoly(fine, quad, 4, cv::Scalar(255), cv::LINE_8, kBits);
            if (i > 0)
                cv::circle(fine, fixed(line[i]), int(std::lround(hw * kScale * (1 << kBits))), cv::Scalar(255),
                           cv::FILLED, cv::LINE_8, kBits);
        }
    }
    cv::Mat fineF, out;
    fine.convertTo(fineF, CV_32F);
    cv::resize(fineF, out, size, 0, 0, cv::INTER_AREA);
    return out;
}

// Error bounds in 1/255 (see MatchesSupersampledArea): edges along the axes, where the box filter is exact and
// only the reference's 1/16 px steps differ; slanted or curved edges and corners, where the estimate differs.
constexpr double kAxisBound = 9, kSlantBound = 26;

struct Errors {
    double max = 0, mean = 0;
};

// Over the pixels either side covers (the empty rest would dilute the mean), leaving out the pixels `skip` marks.
Errors compare(const cv::Mat &coverage, const cv::Mat &reference, const cv::Mat &skip = {})
{
    Errors e;
    int n = 0;
    for (int y = 0; y < coverage.rows; ++y)
        for (int x = 0; x < coverage.cols; ++x) {
            const double ours = coverage.at<uint8_t>(y, x), ref = reference.at<float>(y, x);
            if ((ours == 0 && ref < 0.5) || (!skip.empty() && skip.at<uint8_t>(y, x)))
                continue;
            e.max = std::max(e.max, std::fabs(ours - ref));
            e.mean += std::fabs(ours - ref);
            ++n;
        }
    e.mean /= std::max(n, 1);
    return e;
}

// The pixels two different segments (each as a plain butt-ended quad) cover partly: there the union by max is
// below the union's area (two partial coverages from different sides add up in the area; max keeps the larger),
// so only "never above" holds.
cv::Mat sharedPixels(const std::vector<Line> &lines, double width, cv::Size size)
{
    cv::Mat count = cv::Mat::zeros(size, CV_8UC1);
    for (const Line &line : lines)
        for (size_t i = 0; i + 1 < line.size(); ++i) {
            const cv::Mat area = areaReference({{line[i], line[i + 1]}}, width, size);
            count += (area > 0.5) & (area < 254.5) & cv::Mat::ones(size, CV_8UC1);
        }
    return count >= 2;
}

// The number of pixels above the union's area by more than `slack`.
int aboveUnion(const cv::Mat &coverage, const cv::Mat &reference, double slack)
{
    cv::Mat ours;
    coverage.convertTo(ours, CV_32F);
    return cv::countNonZero(ours > reference + slack);
}

glm::dvec2 direction(double degrees)
{
    const double r = degrees * std::numbers::pi / 180.0;
    return {std::cos(r), std::sin(r)};
}

} // namespace

// Straight strokes at several angles, widths and sub-pixel offsets, butt ends included, against the exact area.
// The box-filter estimate is exact for axis-aligned strokes (the box is separable) and differs from the area where
// a diagonal edge or corner crosses a pixel; the tent of thin strokes is wider than their area. Bounds: the worst
// measured over these cases (printed) with some room; the means are over the pixels either side covers.
TEST(StrokeRaster, MatchesSupersampledArea)
{
    struct Bound {
        double width, max, mean, axisMax;
    };
    const cv::Size size(64, 64);
    for (const Bound bound :
         {Bound{0.7, 32, 22, 30}, Bound{1.5, kSlantBound, 13, kAxisBound}, Bound{2.0, kSlantBound, 8, kAxisBound},
          Bound{3.5, kSlantBound, 7, kAxisBound}, Bound{8.0, kSlantBound, 5, kAxisBound}}) {
        Errors worst, axis;
        for (const double angle : {0.0, 90.0, 30.0, 45.0, 17.0, 63.0})
            for (const glm::dvec2 offset : {glm::dvec2(0, 0), glm::dvec2(0.3, 0.7), glm::dvec2(0.5, 0.25)}) {
                const glm::dvec2 c = glm::dvec2(32, 32) + offset, d = 20.0 * direction(angle);
                const std::vector<Line> lines{{c - d, c + d}};
                const Errors e =
                    compare(rasterize(lines, bound.width, true, size), areaReference(lines, bound.width, size));
                SCOPED_TRACE("width " + std::to_string(bound.width) + " angle " + std::to_string(angle));
                EXPECT_LE(e.max, angle == 0.0 || angle == 90.0 ? bound.axisMax : bound.max);
                EXPECT_LE(e.mean, bound.mean);
                Errors &w = angle == 0.0 || angle == 90.0 ? axis : worst;
                w.max = std::max(w.max, e.max), w.mean = std::max(w.mean, e.mean);
            }
        std::printf("width %.1f: max |error| %.1f/255 (axis-aligned %.1f), worst mean %.2f/255\n", bound.width,
                    worst.max, axis.max, std::max(worst.mean, axis.mean));
    }
}

// Summed across a long stroke in its middle (along rows, or columns for flat strokes, times the sine or cosine that
// turns that cut into a perpendicular one), the coverage is the width: exactly for the box filter on average, to
// within aliasing at a single row.
TEST(StrokeRaster, CoverageAcrossIsTheWidth)
{
    const cv::Size size(256, 256);
    for (const double width : {0.5, 1.0, 1.5, 2.0, 3.5, 8.0})
        for (const double angle : {0.0, 10.0, 30.0, 45.0, 60.0, 80.0, 90.0, 135.0}) {
            SCOPED_TRACE("width " + std::to_string(width) + " angle " + std::to_string(angle));
            const glm::dvec2 c(128.37, 127.81), u = direction(angle);
            const cv::Mat coverage = rasterize({{c - 100.0 * u, c + 100.0 * u}}, width, true, size);
            const bool rows = std::fabs(u.y) >= std::fabs(u.x);
            double total = 0;
            for (int k = -30; k <= 30; ++k) {
                const int i = int(std::lround(rows ? c.y : c.x)) + k;
                const cv::Mat cut = rows ? coverage.row(i) : coverage.col(i);
                const double ink = cv::sum(cut)[0] / 255.0 * (rows ? std::fabs(u.y) : std::fabs(u.x));
                EXPECT_NEAR(ink, width, 0.1) << (rows ? "row " : "column ") << i;
                total += ink;
            }
            // At 45 degrees every row cuts the stroke at the same phase: nothing averages out.
            if (std::fmod(angle, 45.0) != 0.0 || std::fmod(angle, 90.0) == 0.0) {
                EXPECT_NEAR(total / 61, width, 0.02);
            }
        }
}

// Crossing strokes: the crossing is fully covered; where one stroke decides a pixel it matches the area, and where
// two cover it partly (the crossing's inner corners) it never exceeds the union's area (a sum would).
TEST(StrokeRaster, CrossingLinesUniteWithoutDoubleCounting)
{
    const cv::Size size(64, 64);
    const std::vector<Line> two{{{8.0, 30.3}, {56.0, 30.3}}, {{31.6, 8.0}, {31.6, 56.0}}};
    const std::vector<Line> three{two[0], two[1], {{10.2, 9.7}, {53.1, 51.4}}};
    for (const std::vector<Line> &lines : {two, three}) {
        const cv::Mat coverage = rasterize(lines, 3.0, true, size);
        const cv::Mat reference = areaReference(lines, 3.0, size), shared = sharedPixels(lines, 3.0, size);
        EXPECT_EQ(coverage.at<uint8_t>(30, 32), 255);
        const double bound = lines.size() == 2 ? kAxisBound : kSlantBound;
        EXPECT_LE(compare(coverage, reference, shared).max, bound);
        EXPECT_EQ(aboveUnion(coverage, reference, bound), 0);
        EXPECT_GE(cv::countNonZero(shared), 4);
    }
}

// Round joints: a sharp turn and a hairpin have no hole or notch at the joint and match the union of the quads and
// the joint's disc.
TEST(StrokeRaster, JointsAreRoundAndSolid)
{
    const cv::Size size(64, 64);
    const std::vector<std::vector<Line>> cases{{{{10.0, 54.0}, {32.3, 10.6}, {54.0, 54.0}}},
                                               {{{8.0, 30.0}, {50.4, 32.2}, {8.0, 34.0}}}};
    for (const std::vector<Line> &lines : cases) {
        const double width = 6.0;
        const cv::Mat coverage = rasterize(lines, width, true, size);
        const cv::Mat reference = areaReference(lines, width, size);
        const Errors e = compare(coverage, reference, sharedPixels(lines, width, size));
        EXPECT_LE(e.max, kSlantBound);
        EXPECT_LE(e.mean, 6.0);
        EXPECT_EQ(aboveUnion(coverage, reference, kSlantBound), 0);
        const glm::dvec2 joint = lines[0][1];
        for (int y = 0; y < size.height; ++y)
            for (int x = 0; x < size.width; ++x)
                if (glm::distance(glm::dvec2(x, y), joint) <= width / 2 - 0.5) {
                    EXPECT_EQ(coverage.at<uint8_t>(y, x), 255) << x << "," << y;
                }
    }
}

// Butt ends stop at the end point: the end pixel is half covered and nothing lies half a pixel beyond it.
TEST(StrokeRaster, ButtEndsStopAtTheEndPoint)
{
    const cv::Size size(64, 64);
    const cv::Mat flat = rasterize({{{10.0, 20.0}, {40.0, 20.0}}}, 3.0, true, size);
    for (int y = 19; y <= 21; ++y) {
        EXPECT_NEAR(flat.at<uint8_t>(y, 10), 128, 1);
        EXPECT_NEAR(flat.at<uint8_t>(y, 40), 128, 1);
        EXPECT_EQ(flat.at<uint8_t>(y, 9), 0);
        EXPECT_EQ(flat.at<uint8_t>(y, 41), 0);
    }
    for (const double angle : {30.0, 45.0, 100.0}) {
        const glm::dvec2 a(31.3, 30.6), u = direction(angle), b = a + 20.0 * u;
        const cv::Mat coverage = rasterize({{a, b}}, 4.0, true, size);
        int beyond = 0;
        for (int y = 0; y < size.height; ++y)
            for (int x = 0; x < size.width; ++x) {
                const double t = glm::dot(glm::dvec2(x, y) - a, u);
                if (t <= -0.5 || t >= 20.5)
                    beyond += coverage.at<uint8_t>(y, x) != 0;
            }
        EXPECT_EQ(beyond, 0) << angle;
    }
}

// Without anti-aliasing a pixel is 255 exactly when its centre is inside a segment's quad (half-width at least 0.5,
// cv::pointPolygonTest) or within that distance of an interior joint.
TEST(StrokeRaster, BinaryMatchesPixelCentresInside)
{
    const cv::Size size(64, 64);
    std::vector<std::vector<Line>> cases;
    for (const double angle : {0.0, 90.0, 30.0, 45.0, 17.0})
        for (const glm::dvec2 offset : {glm::dvec2(0.13, 0.29), glm::dvec2(0.3, 0.7)}) {
            const glm::dvec2 c = glm::dvec2(32, 32) + offset, d = 20.0 * direction(angle);
            cases.push_back({{c - d, c + d}});
        }
    cases.push_back({{{8.3, 50.2}, {30.1, 12.4}, {55.7, 47.9}, {20.2, 40.6}}});
    // Centres exactly on the edge (both computations exact here) count as inside. (A centre on the edge of a
    // slanted stroke is a tie that rounding decides either way, so the slanted cases avoid them.)
    cases.push_back({{{10.0, 20.0}, {40.0, 20.0}}, {{50.0, 10.0}, {50.0, 50.0}}});
    for (const double width : {0.6, 1.0, 2.0, 3.5, 7.0})
        for (const std::vector<Line> &lines : cases) {
            const cv::Mat coverage = rasterize(lines, width, false, size);
            const double r = std::max(width / 2, 0.5);
            int wrong = 0;
            for (int y = 0; y < size.height; ++y)
                for (int x = 0; x < size.width; ++x) {
                    bool inside = false;
                    for (const Line &line : lines)
                        for (size_t i = 0; i + 1 < line.size(); ++i) {
                            const glm::dvec2 a = line[i], b = line[i + 1];
                            const glm::dvec2 d = (b - a) / glm::distance(a, b), n(-d.y * r, d.x * r);
                            const std::vector<cv::Point2f> quad{{float(a.x + n.x), float(a.y + n.y)},
                                                                {float(b.x + n.x), float(b.y + n.y)},
                                                                {float(b.x - n.x), float(b.y - n.y)},
                                                                {float(a.x - n.x), float(a.y - n.y)}};
                            inside |= cv::pointPolygonTest(quad, cv::Point2f(float(x), float(y)), false) >= 0;
                            inside |= i > 0 && glm::distance(glm::dvec2(x, y), a) <= r;
                        }
                    const uint8_t value = coverage.at<uint8_t>(y, x);
                    ASSERT_TRUE(value == 0 || value == 255);
                    wrong += (value == 255) != inside;
                }
            EXPECT_EQ(wrong, 0) << "width " << width << " from " << lines[0][0].x << "," << lines[0][0].y;
        }
}

// Points are frame pixels; the sink's pixel (0, 0) is frame pixel `origin` and nothing lands outside the clip.
TEST(StrokeRaster, ClipAndOrigin)
{
    const cv::Size size(64, 64);
    const glm::dvec2 origin(100, 50);
    const std::vector<Line> frameLines{{{102.3, 52.1}, {160.2, 95.7}}, {{140.5, 51.0}, {110.0, 110.0}, {150.0, 60.0}}};
    std::vector<Line> sinkLines = frameLines;
    for (Line &line : sinkLines)
        for (glm::dvec2 &p : line)
            p -= origin;
    const LayerRect clip{5, 7, 40, 30};
    const cv::Mat coverage = rasterize(frameLines, 2.5, true, size, origin, clip);
    const cv::Mat reference = areaReference(sinkLines, 2.5, size);
    const cv::Rect inside(clip.x0, clip.y0, clip.x1 - clip.x0, clip.y1 - clip.y0);
    cv::Mat outside = coverage.clone();
    outside(inside).setTo(0);
    EXPECT_EQ(cv::countNonZero(outside), 0);
    EXPECT_GT(cv::countNonZero(coverage(inside)), 100);
    const cv::Mat shared = sharedPixels(sinkLines, 2.5, size);
    EXPECT_LE(compare(coverage(inside), reference(inside), shared(inside)).max, kSlantBound);
    EXPECT_EQ(aboveUnion(coverage(inside), reference(inside), kSlantBound), 0);
    // The same strokes given in sink pixels with no origin: the same pixels.
    EXPECT_EQ(cv::norm(coverage, rasterize(sinkLines, 2.5, true, size, {0, 0}, clip), cv::NORM_INF), 0.0);
}

// A closed loop has no ends: its closing corner is as round as the others.
TEST(StrokeRaster, ClosedLoopHasNoEnds)
{
    const cv::Size size(64, 64);
    const Line square{{10.2, 10.4}, {50.2, 10.4}, {50.2, 50.4}, {10.2, 50.4}, {10.2, 10.4}};
    const cv::Mat coverage = rasterize({square}, 5.0, true, size);
    Line once = square; // the reference's joints are interior points only: go round once more
    once.push_back(square[1]);
    const cv::Mat reference = areaReference({once}, 5.0, size);
    EXPECT_LE(compare(coverage, reference, sharedPixels({square}, 5.0, size)).max, kSlantBound); // round corners
    EXPECT_EQ(aboveUnion(coverage, reference, kSlantBound), 0);
}

// Non-finite and huge coordinates: no crash, nothing outside the clip, the visible parts drawn.
TEST(StrokeRaster, HugeAndNonFinitePoints)
{
    const cv::Size size(64, 64);
    const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
    const std::vector<Line> wild{{{10, 10}, {nan, 5}},          {{inf, 0}, {10, 10}},
                                 {{10, 10}, {-inf, inf}},       {{1e300, 1e300}, {-1e300, -1e300}},
                                 {{1.7e308, 0}, {-1.7e308, 0}}, {{nan, nan}},
                                 {{1e12, -1e12}, {-1e12, 1e12}}};
    for (const bool antialias : {true, false})
        rasterize(wild, 3.0, antialias, size); // the sink's checks run inside
    // Visible parts: a diagonal towards 1e12, a horizontal line between +-1e12, and two runs split by a NaN.
    const std::vector<Line> visible{{{10.3, 10.1}, {1e12, 1e12 + 0.2}},
                                    {{-1e12, 20.5}, {1e12, 20.5}},
                                    {{5.2, 40.1}, {20.3, 55.2}, {nan, nan}, {40.1, 40.3}, {50.2, 58.3}}};
    const std::vector<Line> expected{{{10.3, 10.1}, {100.0, 100.0 + 0.2 * 90 / (1e12 - 10)}},
                                     {{-50.0, 20.5}, {120.0, 20.5}},
                                     {{5.2, 40.1}, {20.3, 55.2}},
                                     {{40.1, 40.3}, {50.2, 58.3}}};
    // A stroke wider than the frame (a point near the camera) covers all of it.
    for (const bool antialias : {true, false})
        EXPECT_EQ(cv::countNonZero(rasterize({{{-1e12, 20.0}, {1e12, 30.0}}}, 1e9, antialias, size) != 255), 0);
    const cv::Mat coverage = rasterize(visible, 3.0, true, size);
    const cv::Mat reference = areaReference(expected, 3.0, size);
    EXPECT_LE(compare(coverage, reference, sharedPixels(expected, 3.0, size)).max, kSlantBound);
    EXPECT_NEAR(cv::sum(coverage)[0], cv::sum(reference)[0], 0.01 * cv::sum(reference)[0]);
}

// Degenerate input draws nothing at all.
TEST(StrokeRaster, DegenerateInputDrawsNothing)
{
    const LayerRect clip{0, 0, 32, 32};
    const auto calls = [&](const std::vector<Line> &lines, double width, LayerRect c) {
        RecordingSink sink(32, 32, c);
        StrokeRasterizer raster;
        raster.rasterize(polylines(lines), width, true, {0, 0}, c, sink);
        return sink.calls;
    };
    EXPECT_EQ(calls({{{10, 10}}}, 2.0, clip), 0);
    EXPECT_EQ(calls({{{10, 10}, {10, 10}, {10, 10}}}, 2.0, clip), 0);
    for (const double width :
         {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()})
        EXPECT_EQ(calls({{{10, 10}, {20, 20}}}, width, clip), 0);
    EXPECT_EQ(calls({{{10, 10}, {20, 20}}}, 2.0, LayerRect{5, 5, 5, 30}), 0);
    EXPECT_EQ(calls({{{100, 100}, {200, 100}}}, 2.0, clip), 0);
}

// The work follows the stroke, not its bounding box: a long diagonal in a large clip emits only pixels near it, in
// one call per row.
TEST(StrokeRaster, EmitsOnlyNearTheStroke)
{
    const LayerRect clip{0, 0, 3000, 3000};
    RecordingSink sink(0, 0, clip);
    StrokeRasterizer raster;
    raster.rasterize(polylines({{{1.5, 2.5}, {2990.5, 2900.7}}}), 2.0, true, {0, 0}, clip, sink);
    EXPECT_TRUE(sink.problems.empty());
    EXPECT_LE(sink.calls, 2910);
    EXPECT_LE(sink.pixels, 2910 * 5);
    EXPECT_GE(sink.pixels, 2900 * 2);
}

// The documented formula evaluated at every pixel centre directly (max over segments; no clipping, runs, sorting,
// merging or vector kernels): the sweep must find every pixel it covers and give it the same value. Random
// polylines (closed, horizontal and vertical ones too), widths 0.2-20, with and without anti-aliasing. The
// formula itself is held to the exact area by the tests above.
namespace {

double formulaCoverage(const std::vector<Line> &lines, double width, bool antialias, glm::dvec2 p)
{
    const double hw = width / 2;
    double best = 0;
    for (const Line &line : lines) {
        const bool closed = line.size() > 2 && line.front() == line.back();
        for (size_t i = 0; i + 1 < line.size(); ++i) {
            const glm::dvec2 a = line[i], b = line[i + 1];
            const double length = glm::distance(a, b);
            const glm::dvec2 u = (b - a) / length;
            const double t = glm::dot(p - a, u), s = u.x * (p.y - a.y) - u.y * (p.x - a.x);
            const bool roundA = closed || i > 0, roundB = closed || i + 2 < line.size();
            const double d = t < 0 && roundA        ? glm::distance(p, a)
                             : t > length && roundB ? glm::distance(p, b)
                                                    : std::fabs(s);
            double c = 0;
            if (!antialias) {
                c = (roundA || t >= 0) && (roundB || t <= length) && d <= std::max(hw, 0.5);
            } else {
                c = width < 1 ? width * std::clamp(1 - d, 0.0, 1.0) : std::clamp(hw + 0.5 - d, 0.0, 1.0);
                c *= roundA ? 1.0 : std::clamp(0.5 + t, 0.0, 1.0);
                c *= roundB ? 1.0 : std::clamp(0.5 + length - t, 0.0, 1.0);
            }
            best = std::max(best, c);
        }
    }
    return 255 * best;
}

} // namespace

TEST(StrokeRaster, SweepMatchesDirectEvaluation)
{
    std::mt19937 engine(7);
    std::uniform_real_distribution<double> uniform(0, 1);
    const cv::Size size(64, 48);
    int worst = 0;
    for (int round = 0; round < 300; ++round) {
        std::vector<Line> lines(1 + engine() % 3);
        for (Line &line : lines) {
            for (unsigned i = 0, n = 2 + engine() % 5; i < n; ++i)
                line.push_back({uniform(engine) * 80 - 10, uniform(engine) * 60 - 10});
            if (engine() % 4 == 0)
                line.push_back(line.front());
            for (glm::dvec2 &p : line) {
                if (round % 6 == 1)
                    p.y = line[0].y;
                if (round % 6 == 2)
                    p.x = std::round(line[0].x);
            }
        }
        const double width = std::pow(10.0, uniform(engine) * 2 - 0.7);
        const bool antialias = round % 4 != 0;
        const cv::Mat coverage = rasterize(lines, width, antialias, size);
        for (int y = 0; y < size.height; ++y)
            for (int x = 0; x < size.width; ++x) {
                const int expected = int(formulaCoverage(lines, width, antialias, glm::dvec2(x, y)) + 0.5);
                worst = std::max(worst, std::abs(expected - coverage.at<uint8_t>(y, x)));
            }
    }
    EXPECT_LE(worst, 1); // float kernels against double
}

} // namespace overlayd
