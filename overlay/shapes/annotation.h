// SPDX-License-Identifier: Apache-2.0
// The annotation model: what a user asks to be drawn, in world units (metres) in a named scene-graph frame, or in
// screen pixels. Plain data: config/ fills it, overlay/ projects and rasterizes it.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "media/rgba.h"
#include "overlay/shapes/primitives.h"
#include "projection/pose.h"
#include "projection/projection.h"
#include "projection/scene_graph.h"

namespace overlayd {

inline constexpr Rgba kRed{255, 0, 0, 255}, kGreen{0, 255, 0, 255}, kBlue{0, 0, 255, 255}, kWhite{255, 255, 255, 255};

// The shortest dash period (on + off + ...) in pixels: a finer pattern cannot be seen, and walking it would cost one
// step per interval (a 1e-9 px dash along a 1000 px line is 10^12 steps). The config refuses a shorter one; the
// renderer draws one it is given anyway as solid, so no scene can make it loop without end.
inline constexpr double kMinDashPeriodPx = 1.0;

struct Style {
    Rgba colour = kWhite;
    double width = 2.0;         // pixels, fractional allowed
    std::vector<double> dash{}; // on, off, on, off... in pixels along the drawn curve; empty: solid
    bool antialias = true;
    std::string layer = "default"; // layers are switched on and off at runtime by name
};

struct AxesShape {
    double length = 1.0;
    std::array<Rgba, 3> colours{kRed, kGreen, kBlue}; // X, Y, Z
    bool labels = false;                              // "X", "Y", "Z" at the tips
};

// Lines u = i * spacing and v = j * spacing on the plane origin + u * axisU + v * axisV, for |u| <= extentU and
// |v| <= extentV. Every majorEvery-th line (counted from the origin) uses majorStyle.
struct GridShape {
    glm::dvec3 origin{0.0};
    glm::dvec3 axisU{1.0, 0.0, 0.0}, axisV{0.0, 1.0, 0.0};
    double spacing = 1.0;
    double extentU = 10.0, extentV = 10.0;
    unsigned majorEvery = 0; // 0: no major lines
    std::optional<Style> majorStyle{};
};

// The most points a polyline or markers annotation holds (the config's and a live path file's limit).
inline constexpr size_t kMaxWorldPoints = 10000;

struct PolylineShape {
    std::vector<glm::dvec3> points;
    bool closed = false;
};

enum class MarkerKind { Cross, Plus, Circle, Square };
struct MarkersShape {
    std::vector<glm::dvec3> points;
    MarkerKind kind = MarkerKind::Cross;
    double sizePx = 10.0;
};

struct BoxShape {
    glm::dvec3 centre{0.0};
    glm::dvec3 size{1.0};
    glm::dquat rotation{1.0, 0.0, 0.0, 0.0};
};

// A circle (or an arc from startDeg to endDeg, counter-clockwise from axisU towards axisV) on a plane.
struct ArcShape {
    glm::dvec3 centre{0.0};
    glm::dvec3 axisU{1.0, 0.0, 0.0}, axisV{0.0, 1.0, 0.0};
    double radius = 1.0;
    double startDeg = 0.0, endDeg = 360.0;
};

struct LabelShape {
    glm::dvec3 anchor{0.0};
    std::string text;
    glm::dvec2 offsetPx{0.0}; // in the viewport's origin convention
    double sizePx = 16.0;     // text height
    std::optional<Rgba> background{};
    TextAlign align = TextAlign::Left; // which column of the box sits at the anchor + offset
};

// Where the plane through `point` with `normal` meets infinity, drawn across the view.
struct HorizonShape {
    glm::dvec3 normal{0.0, 0.0, 1.0};
};

// Reverse-camera guide lines: the ground track of a car-like vehicle (Ackermann geometry) for a steering angle,
// starting at the rear axle (the frame's origin, x forward, y left, z up) and going backwards for `length`
// metres; one line per rear wheel edge plus distance marks across the track. A live steering input ([[input.can]])
// sets steeringDeg through steeringRatio; while its value is unknown (stale, out of range) the wheel tracks are not
// drawn and the marks lie straight behind the car in staleColour, so a wrong curve is never shown as true.
struct GuideLinesShape {
    double wheelbase = 2.7;
    double trackWidth = 1.6;
    double steeringDeg = 0.0; // front-wheel angle, positive turns left
    double length = 5.0;
    std::vector<double> distanceMarks{1.0, 2.0, 3.0};
    std::vector<Rgba> markColours{}; // per distance mark; empty: the style's colour
    double steeringRatio = 1.0;      // steering-wheel angle / road-wheel angle, for a live steering input
    bool steeringKnown = true;
    Rgba staleColour{158, 158, 158, 255};
};

// Another camera's frustum as a wireframe, from its pose and projection matrix (Projection::matrix()), cut at
// farDistance metres in front of it.
struct FrustumShape {
    Pose pose{};
    glm::dmat4 projection{1.0};
    DepthRange depth = DepthRange::MinusOneToOne;
    double farDistance = 2.0;
};

// An image's pixels as decoded from its file: rows of width * 4 bytes, R G B A, colour premultiplied by A. Shared by
// every renderer of the scene (a reload decodes the file again).
struct ImagePixels {
    unsigned width = 0, height = 0;
    std::vector<uint8_t> rgba;
};

// An image (a logo, a sign, a map): on the screen, with its corner nearest the viewport's origin at `position`
// (upright under either origin) and `sizePx` (default: the image's own size); or on a plane in the world, centred
// at `anchor` in the annotation's frame, `size` metres along axisU (the image's rows, left to right) and axisV (its
// columns, bottom to top). Drawn above the world layers, below token text.
struct ImageShape {
    std::shared_ptr<const ImagePixels> image;
    std::optional<glm::dvec2> position{};
    std::optional<glm::dvec2> sizePx{};
    std::optional<glm::dvec3> anchor{};
    glm::dvec2 size{1.0, 1.0};
    glm::dvec3 axisU{1.0, 0.0, 0.0}, axisV{0.0, 1.0, 0.0};
    double opacity = 1.0;
};

// Screen-space items, in pixels of the viewport, in its origin convention.
// Text tokens: {frame} (sequence number), {fps}, {time:FORMAT} (strftime of the frame's wall clock, e.g.
// {time:%Y-%m-%d %H:%M:%S}), {ms} (milliseconds of the wall clock), {{ and }} for literal braces.
struct ScreenTextShape {
    std::string text;
    glm::dvec2 position{10.0, 10.0}; // the text box's corner nearest the origin (its column per `align`)
    double sizePx = 20.0;
    std::optional<Rgba> background{};
    TextAlign align = TextAlign::Left;
};
struct CrosshairShape {
    std::optional<glm::dvec2> position{}; // default: the viewport centre
    double sizePx = 20.0;
};
struct RectShape {
    glm::dvec2 position{0.0}, size{10.0};
    bool filled = false;
};

// The fewest and most points of a privacy mask's polygon, and the range of its pixelation block.
inline constexpr size_t kMinMaskPoints = 3;
inline constexpr size_t kMaxMaskPoints = 1024;
inline constexpr unsigned kMinMaskBlockPx = 2;
inline constexpr unsigned kMaxMaskBlockPx = 256;

// A privacy mask: a polygon burned into the frame before anything else sees it (overlay/privacy_masks.h), filled
// with a colour or pixelated in blocks. On the screen (`world` false: points are [x, y] pixels in the viewport's
// origin, z unused) or on the world (points in the annotation's frame, projected through the live camera). Any
// polygon, convex or not; a self-crossing one is filled by the nonzero winding rule. No layer switch hides it.
struct MaskShape {
    std::vector<glm::dvec3> points;
    bool world = false;
    std::optional<Rgba> fill{}; // nullopt: pixelate
    unsigned blockPx = 16;
};

using Shape =
    std::variant<AxesShape, GridShape, PolylineShape, MarkersShape, BoxShape, ArcShape, LabelShape, HorizonShape,
                 GuideLinesShape, FrustumShape, ScreenTextShape, CrosshairShape, RectShape, ImageShape, MaskShape>;

struct Annotation {
    std::string name;                       // for logs and error messages
    std::string frame = SceneGraph::kWorld; // the scene-graph frame its coordinates are in (ignored by screen items)
    Style style{};
    Shape shape;
};

inline bool isMask(const Annotation &annotation)
{
    return std::holds_alternative<MaskShape>(annotation.shape);
}

// The points of a polyline or markers annotation (what [[input.path]] replaces); null for other shapes.
inline std::vector<glm::dvec3> *worldPointsOf(Annotation &annotation)
{
    if (auto *polyline = std::get_if<PolylineShape>(&annotation.shape))
        return &polyline->points;
    if (auto *markers = std::get_if<MarkersShape>(&annotation.shape))
        return &markers->points;
    return nullptr;
}

// Everything drawn on a stream: the frames annotations refer to and the annotations, in drawing order.
struct OverlayScene {
    std::vector<FrameSpec> frames;
    std::vector<Annotation> annotations;
    // `frames` resolved, by the config loader (which has to, to check frame names); a scene made in code leaves it
    // empty and the renderer resolves the frames itself.
    std::optional<SceneGraph> graph{};
};

} // namespace overlayd
