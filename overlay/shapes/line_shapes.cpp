// SPDX-License-Identifier: Apache-2.0
// Builders for the shapes made of 3D lines: axes, grid, polyline, box, arc.
#include "overlay/shapes/shape_context.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <glm/gtc/quaternion.hpp>

namespace overlayd {

namespace {

// Pixels between an axis tip and its label.
constexpr double kAxisLabelGapPx = 4.0;
// An axis label's size: at least this, and this many times the axis's line width.
constexpr double kMinAxisLabelPx = 16.0;
constexpr double kAxisLabelPerWidth = 6.0;
// Relative luminance (sRGB, approximated by gamma 2.2) under which a label's colour counts as dark: it gets a light
// plate (blue 0.07, red 0.21), else a dark one (green 0.72, yellow 0.93).
constexpr double kDarkLabelLuminance = 0.4;
constexpr Rgba kLightPlate{255, 255, 255, 200};
constexpr Rgba kDarkPlate{0, 0, 0, 160};

// A plate behind an axis label that contrasts with its colour whatever the ground is: blue "Z" on dark squares, or
// green "Y" on grass, stays readable.
Rgba plateFor(Rgba colour)
{
    const auto linear = [](uint8_t c) {
        return std::pow(c / 255.0, 2.2);
    };
    const double luminance = 0.2126 * linear(colour.r) + 0.7152 * linear(colour.g) + 0.0722 * linear(colour.b);
    return luminance < kDarkLabelLuminance ? kLightPlate : kDarkPlate;
}

} // namespace

void buildAxes(const ShapeContext &ctx, const AxesShape &shape)
{
    static const char *const kNames[] = {"X", "Y", "Z"};
    for (int axis = 0; axis < 3; ++axis) {
        glm::dvec3 tip(0.0);
        tip[axis] = shape.length;
        ctx.segment(ctx.stroke(shape.colours[axis]), glm::dvec3(0.0), tip);
        if (!shape.labels)
            continue;
        if (const auto pixel = ctx.point(tip)) {
            const double size = std::max(kMinAxisLabelPx, kAxisLabelPerWidth * ctx.style.width);
            ctx.text(kNames[axis], *pixel + ctx.camera.viewport().offsetToTopLeft(glm::dvec2(kAxisLabelGapPx)), size,
                     shape.colours[axis], plateFor(shape.colours[axis]));
        }
    }
}

void buildGrid(const ShapeContext &ctx, const GridShape &shape)
{
    StrokeItem *minor = &ctx.stroke();
    StrokeItem *major = minor;
    if (shape.majorEvery > 0 && shape.majorStyle) {
        const Style &s = *shape.majorStyle;
        ctx.out.strokes.push_back({StrokeStyle{s.colour, s.width, s.dash, s.antialias}, Polylines{}});
        major = &ctx.out.strokes.back();
        minor = &ctx.out.strokes[ctx.out.strokes.size() - 2]; // push_back may have moved it
    }
    const auto lines = [&](const glm::dvec3 &along, const glm::dvec3 &across, double extentAlong, double extentAcross) {
        const long count = long(std::floor(extentAcross / shape.spacing + 1e-9));
        for (long i = -count; i <= count; ++i) {
            const glm::dvec3 centre = shape.origin + double(i) * shape.spacing * across;
            const bool isMajor = shape.majorEvery > 0 && i % long(shape.majorEvery) == 0;
            ctx.segment(isMajor ? *major : *minor, centre - extentAlong * along, centre + extentAlong * along);
        }
    };
    lines(shape.axisV, shape.axisU, shape.extentV, shape.extentU); // u = const
    lines(shape.axisU, shape.axisV, shape.extentU, shape.extentV); // v = const
}

void buildPolyline(const ShapeContext &ctx, const PolylineShape &shape)
{
    ctx.polyline(ctx.stroke(), shape.points, shape.closed);
}

void buildBox(const ShapeContext &ctx, const BoxShape &shape)
{
    const glm::dmat3 rotation = glm::mat3_cast(glm::normalize(shape.rotation));
    std::array<glm::dvec3, 8> corners;
    for (int i = 0; i < 8; ++i) {
        const glm::dvec3 sign((i & 1) ? 0.5 : -0.5, (i & 2) ? 0.5 : -0.5, (i & 4) ? 0.5 : -0.5);
        corners[i] = shape.centre + rotation * (sign * shape.size);
    }
    StrokeItem &item = ctx.stroke();
    // Corners i and j share an edge when their indices differ in exactly one bit.
    for (int i = 0; i < 8; ++i) {
        for (int bit : {1, 2, 4}) {
            if (!(i & bit))
                ctx.segment(item, corners[i], corners[i | bit]);
        }
    }
}

void buildArc(const ShapeContext &ctx, const ArcShape &shape)
{
    // Chords of 3 degrees: the sagitta is r * 3.4e-4, under a pixel for any circle smaller than ~3000 px across.
    constexpr double kStepDeg = 3.0;
    const double sweep = shape.endDeg - shape.startDeg;
    const bool full = std::abs(sweep) >= 360.0;
    const int steps = std::max(1, int(std::ceil(std::abs(sweep) / kStepDeg)));
    std::vector<glm::dvec3> points;
    for (int i = 0; i <= (full ? steps - 1 : steps); ++i) {
        const double angle = glm::radians(shape.startDeg + sweep * i / steps);
        points.push_back(shape.centre + shape.radius * (std::cos(angle) * shape.axisU + std::sin(angle) * shape.axisV));
    }
    ctx.polyline(ctx.stroke(), points, full);
}

} // namespace overlayd
