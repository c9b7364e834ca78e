// SPDX-License-Identifier: Apache-2.0
// The rules each shape's numbers must follow; the message names the annotation and the value.
#include "overlay/shapes/scene_checks.h"

#include <cmath>
#include <string>

#include "overlay/shapes/shape_builder.h"
#include "overlay/shapes/text_tokens.h"

namespace overlayd {

namespace {

// Sizes beyond this (pixels, or lines in a grid) are refused: they would only be typing mistakes, and they keep
// every pixel coordinate far inside int range.
constexpr double kMaxPixels = 1e5;
constexpr double kMaxGridLines = 2000;

bool finite(double v)
{
    return std::isfinite(v);
}
bool finite(const glm::dvec2 &v)
{
    return finite(v.x) && finite(v.y);
}
bool finite(const glm::dvec3 &v)
{
    return finite(v.x) && finite(v.y) && finite(v.z);
}
bool positive(double v, double limit = kMaxPixels)
{
    return finite(v) && v > 0.0 && v <= limit;
}

// Each rule names the annotation key it is about, so that the config loader can point at the value.
struct Checker {
    AnnotationProblem found; // the first problem

    void require(bool ok, std::string_view key, const std::string &what)
    {
        if (!ok && found.message.empty())
            found = AnnotationProblem{std::string(key), what};
    }
    void style(const Style &s, std::string_view prefix)
    {
        const std::string at(prefix);
        require(positive(s.width, 1000.0), at + ".width",
                "line width must be in (0, 1000] px (got " + std::to_string(s.width) + ")");
        double period = 0.0;
        for (double d : s.dash) {
            require(finite(d) && d >= 0.0 && d <= kMaxPixels, at + ".dash", "dash lengths must be in [0, 100000] px");
            period += finite(d) && d > 0.0 ? d : 0.0;
        }
        require(s.dash.empty() || period >= kMinDashPeriodPx, at + ".dash",
                "a dash pattern must add up to at least " + std::to_string(int(kMinDashPeriodPx)) +
                    " px (a finer one cannot be seen; use [] for solid)");
    }
    void points(const std::vector<glm::dvec3> &ps)
    {
        for (const glm::dvec3 &p : ps)
            require(finite(p), "points", "points must be finite");
        require(ps.size() <= kMaxWorldPoints, "points", "at most " + std::to_string(kMaxWorldPoints) + " points");
    }
    void text(const std::string &t, double sizePx)
    {
        require(positive(sizePx, 1000.0), "size_px", "text size must be in (0, 1000] px");
        if (Status s = checkTokens(t); !s)
            require(false, "text", s.error().message);
    }
    void check(const AxesShape &s);
    void check(const GridShape &s);
    void check(const PolylineShape &s);
    void check(const MarkersShape &s);
    void check(const BoxShape &s);
    void check(const ArcShape &s);
    void check(const LabelShape &s);
    void check(const HorizonShape &s);
    void check(const GuideLinesShape &s);
    void check(const FrustumShape &s);
    void check(const ScreenTextShape &s);
    void check(const CrosshairShape &s);
    void check(const RectShape &s);
    void check(const ImageShape &s);
    void check(const MaskShape &s);
};

void Checker::check(const AxesShape &s)
{
    require(positive(s.length, 1e9), "length", "axes length must be > 0");
}

void Checker::check(const GridShape &s)
{
    require(finite(s.origin) && finite(s.axisU) && finite(s.axisV), "origin", "grid vectors must be finite");
    require(positive(s.spacing, 1e9) && finite(s.extentU) && finite(s.extentV) && s.extentU >= 0 && s.extentV >= 0,
            "spacing", "grid spacing must be > 0 and extents >= 0");
    require(s.spacing > 0 && (s.extentU + s.extentV) / s.spacing <= kMaxGridLines, "spacing",
            "grid has more than 4000 lines (extent / spacing too large)");
    if (s.majorStyle)
        style(*s.majorStyle, "major_style");
}

void Checker::check(const PolylineShape &s)
{
    points(s.points);
}

void Checker::check(const MarkersShape &s)
{
    points(s.points);
    require(positive(s.sizePx), "size_px", "marker size must be > 0 px");
}

void Checker::check(const BoxShape &s)
{
    require(finite(s.centre) && finite(s.size) && std::isfinite(glm::length(s.rotation)) && glm::length(s.rotation) > 0,
            "size", "box centre, size and rotation must be finite (rotation non-zero)");
}

void Checker::check(const ArcShape &s)
{
    require(finite(s.centre) && finite(s.axisU) && finite(s.axisV) && positive(s.radius, 1e9) && finite(s.startDeg) &&
                finite(s.endDeg) && std::abs(s.endDeg - s.startDeg) <= 3600,
            "radius", "arc centre/axes must be finite, radius > 0, |end - start| <= 3600 degrees");
}

void Checker::check(const LabelShape &s)
{
    require(finite(s.anchor) && finite(s.offsetPx) && glm::length(s.offsetPx) < kMaxPixels, "offset_px",
            "label anchor and offset must be finite");
    text(s.text, s.sizePx);
}

void Checker::check(const HorizonShape &s)
{
    require(finite(s.normal) && glm::length(s.normal) > 0, "normal", "horizon normal must be finite and non-zero");
}

void Checker::check(const GuideLinesShape &s)
{
    require(positive(s.wheelbase, 100) && positive(s.trackWidth, 100) && positive(s.length, 1000) &&
                finite(s.steeringDeg) && std::abs(s.steeringDeg) < 89 && positive(s.steeringRatio, 100),
            "wheelbase",
            "guide lines need wheelbase, track width, length and steering ratio > 0 and |steering| < 89 degrees");
    for (double d : s.distanceMarks)
        require(finite(d), "distance_marks", "distance marks must be finite");
}

void Checker::check(const FrustumShape &s)
{
    require(positive(s.farDistance, 1e9) && std::abs(glm::determinant(s.projection)) > 0 &&
                std::isfinite(glm::determinant(s.projection)),
            "camera", "frustum needs farDistance > 0 and an invertible projection matrix");
}

void Checker::check(const ScreenTextShape &s)
{
    require(finite(s.position) && glm::length(s.position) < kMaxPixels, "position", "text position must be finite");
    text(s.text, s.sizePx);
}

void Checker::check(const CrosshairShape &s)
{
    require(positive(s.sizePx) && (!s.position || (finite(*s.position) && glm::length(*s.position) < kMaxPixels)),
            "size_px", "crosshair size must be > 0 and its position finite");
}

void Checker::check(const RectShape &s)
{
    require(finite(s.position) && glm::length(s.position) < kMaxPixels && positive(s.size.x) && positive(s.size.y),
            "size", "rect position must be finite and its size > 0");
}

void Checker::check(const ImageShape &s)
{
    require(s.image && s.image->width > 0 && s.image->height > 0 &&
                s.image->rgba.size() == size_t(s.image->width) * s.image->height * 4,
            "path", "image has no pixels");
    require(s.position.has_value() != s.anchor.has_value(), "position",
            "image needs either a screen position or a world anchor");
    if (s.position)
        require(
            finite(*s.position) && glm::length(*s.position) < kMaxPixels &&
                (!s.sizePx || (positive(s.sizePx->x) && positive(s.sizePx->y) && glm::length(*s.sizePx) < kMaxPixels)),
            "size_px", "image position must be finite and its size > 0");
    if (s.anchor)
        require(finite(*s.anchor) && positive(s.size.x) && positive(s.size.y) &&
                    glm::length(glm::cross(s.axisU, s.axisV)) > 1e-9,
                "size", "image anchor must be finite, its size > 0 and its axes non-zero and not parallel");
    require(s.opacity >= 0.0 && s.opacity <= 1.0, "opacity", "image opacity must be 0..1");
}

void Checker::check(const MaskShape &s)
{
    require(s.points.size() >= kMinMaskPoints && s.points.size() <= kMaxMaskPoints, "points",
            "a mask needs " + std::to_string(kMinMaskPoints) + " to " + std::to_string(kMaxMaskPoints) + " points");
    for (const glm::dvec3 &p : s.points)
        require(finite(p) && (s.world || glm::length(glm::dvec2(p)) < kMaxPixels), "points",
                "mask points must be finite (screen points within 100000 px)");
    require(s.fill || (s.blockPx >= kMinMaskBlockPx && s.blockPx <= kMaxMaskBlockPx), "block_px",
            "block_px must be " + std::to_string(kMinMaskBlockPx) + " to " + std::to_string(kMaxMaskBlockPx));
    require(!s.fill || s.fill->a == 255, "fill", "a mask's fill colour must be opaque");
}

} // namespace

std::optional<AnnotationProblem> checkAnnotation(const Annotation &annotation)
{
    Checker checker;
    checker.style(annotation.style, "style");
    std::visit([&](const auto &shape) { checker.check(shape); }, annotation.shape);
    if (checker.found.message.empty())
        return std::nullopt;
    return checker.found;
}

Status checkScene(const OverlayScene &scene, const SceneGraph &graph)
{
    for (const Annotation &annotation : scene.annotations) {
        if (const auto problem = checkAnnotation(annotation))
            return makeError(ErrorCode::InvalidArgument, "annotation \"" + annotation.name + "\": " + problem->message);
        const bool screen =
            std::holds_alternative<ScreenTextShape>(annotation.shape) ||
            std::holds_alternative<CrosshairShape>(annotation.shape) ||
            std::holds_alternative<RectShape>(annotation.shape) ||
            (isMask(annotation) && !std::get<MaskShape>(annotation.shape).world) ||
            (std::holds_alternative<ImageShape>(annotation.shape) && std::get<ImageShape>(annotation.shape).position);
        if (!screen && !graph.contains(annotation.frame))
            return makeError(ErrorCode::InvalidArgument,
                             "annotation \"" + annotation.name + "\": unknown frame \"" + annotation.frame + "\"");
    }
    return Ok{};
}

std::vector<std::string> textSlotNames(const OverlayScene &scene)
{
    std::vector<std::string> names;
    for (const Annotation &annotation : scene.annotations)
        if (const auto *text = std::get_if<ScreenTextShape>(&annotation.shape))
            appendSlotNames(text->text, names);
    return names;
}

} // namespace overlayd
