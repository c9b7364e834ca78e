// SPDX-License-Identifier: Apache-2.0
// The shape keys of an [[annotation]], one reader per type of overlay/shapes/annotation.h.
#include "config/config_sections.h"

#include <algorithm>
#include <array>

#include "config/limits.h"

namespace overlayd {

namespace {

void requireKeys(TableReader &table, const std::array<std::string_view, 2> &keys, const std::string &type)
{
    for (std::string_view key : keys)
        if (!key.empty() && !table.has(key))
            table.problem(key, "missing: a " + type + " annotation needs it");
}

void readPlane(TableReader &table, glm::dvec3 &axisU, glm::dvec3 &axisV)
{
    axisU = table.vec3("axis_u").value_or(axisU);
    axisV = table.vec3("axis_v").value_or(axisV);
    if (glm::length(glm::cross(axisU, axisV)) < 1e-9)
        table.problem(table.has("axis_v") ? "axis_v" : "axis_u", "axis_u and axis_v must be non-zero and not parallel");
}

Shape readAxes(TableReader &t)
{
    AxesShape s;
    s.length = t.positive("length", 1e6).value_or(s.length);
    if (auto colours = t.colours("colours")) {
        if (colours->size() == 3)
            std::copy(colours->begin(), colours->end(), s.colours.begin());
        else
            t.problem("colours", "expected 3 colours (X, Y, Z)");
    }
    s.labels = t.boolean("labels").value_or(s.labels);
    return s;
}

Shape readGrid(TableReader &t)
{
    GridShape s;
    s.origin = t.vec3("origin").value_or(s.origin);
    readPlane(t, s.axisU, s.axisV);
    s.spacing = t.positive("spacing", 1e6).value_or(s.spacing);
    if (auto extent = t.positive("extent", 1e6))
        s.extentU = s.extentV = *extent;
    s.extentU = t.positive("extent_u", 1e6).value_or(s.extentU);
    s.extentV = t.positive("extent_v", 1e6).value_or(s.extentV);
    s.majorEvery = unsigned(t.integer("major_every", 0, 10000).value_or(0));
    if (auto major = t.table("major_style"))
        s.majorStyle = readStyle(*major, Style{});
    return s;
}

Shape readPolyline(TableReader &t)
{
    PolylineShape s;
    s.points = t.points("points", kMaxWorldPoints).value_or(s.points);
    if (t.has("points") && s.points.size() < 2)
        t.problem("points", "a polyline needs at least 2 points");
    s.closed = t.boolean("closed").value_or(s.closed);
    return s;
}

Shape readMarkers(TableReader &t)
{
    MarkersShape s;
    s.points = t.points("points", kMaxWorldPoints).value_or(s.points);
    s.kind = t.choice<MarkerKind>("marker", {{"cross", MarkerKind::Cross},
                                             {"plus", MarkerKind::Plus},
                                             {"circle", MarkerKind::Circle},
                                             {"square", MarkerKind::Square}})
                 .value_or(s.kind);
    s.sizePx = t.positive("size_px", 10000).value_or(s.sizePx);
    return s;
}

Shape readBox(TableReader &t)
{
    BoxShape s;
    s.centre = t.vec3("centre").value_or(s.centre);
    s.size = t.vec3("size").value_or(s.size);
    if (s.size.x <= 0 || s.size.y <= 0 || s.size.z <= 0)
        t.problem("size", "box sizes must be > 0 metres");
    s.rotation = readRotation(t, "rotation").value_or(s.rotation);
    return s;
}

Shape readArc(TableReader &t)
{
    ArcShape s;
    s.centre = t.vec3("centre").value_or(s.centre);
    readPlane(t, s.axisU, s.axisV);
    s.radius = t.positive("radius", 1e6).value_or(s.radius);
    s.startDeg = t.number("start_deg", -3600, 3600).value_or(s.startDeg);
    s.endDeg = t.number("end_deg", -3600, 3600).value_or(s.endDeg);
    return s;
}

TextAlign readAlign(TableReader &t)
{
    return t
        .choice<TextAlign>("align", {{"left", TextAlign::Left},
                                     {"centre", TextAlign::Centre},
                                     {"center", TextAlign::Centre},
                                     {"right", TextAlign::Right}})
        .value_or(TextAlign::Left);
}

Shape readLabel(TableReader &t)
{
    LabelShape s;
    s.anchor = t.vec3("anchor").value_or(s.anchor);
    s.text = t.string("text", kMaxAnnotationTextBytes).value_or("");
    s.offsetPx = t.vec2("offset_px").value_or(s.offsetPx);
    s.sizePx = t.positive("size_px", 1000).value_or(s.sizePx);
    s.background = t.colour("background");
    s.align = readAlign(t);
    return s;
}

Shape readHorizon(TableReader &t)
{
    HorizonShape s;
    s.normal = t.vec3("normal").value_or(s.normal);
    if (glm::length(s.normal) < 1e-12)
        t.problem("normal", "the plane normal must not be zero");
    return s;
}

Shape readGuideLines(TableReader &t)
{
    GuideLinesShape s;
    s.wheelbase = t.positive("wheelbase", 100).value_or(s.wheelbase);
    s.trackWidth = t.positive("track_width", 100).value_or(s.trackWidth);
    s.steeringDeg = t.number("steering_deg", -80, 80).value_or(s.steeringDeg);
    s.length = t.positive("length", 1000).value_or(s.length);
    s.distanceMarks = t.numbers("distance_marks", kMaxDistanceMarks, Range{0.0, 1000.0}).value_or(s.distanceMarks);
    s.markColours = t.colours("mark_colours").value_or(s.markColours);
    s.steeringRatio = t.positive("steering_ratio", 100).value_or(s.steeringRatio);
    s.staleColour = t.colour("stale_colour").value_or(s.staleColour);
    return s;
}

Shape readScreenText(TableReader &t)
{
    ScreenTextShape s;
    s.text = t.string("text", kMaxAnnotationTextBytes).value_or("");
    s.position = t.vec2("position").value_or(s.position);
    s.sizePx = t.positive("size_px", 1000).value_or(s.sizePx);
    s.background = t.colour("background");
    s.align = readAlign(t);
    return s;
}

Shape readCrosshair(TableReader &t)
{
    CrosshairShape s;
    s.position = t.vec2("position");
    s.sizePx = t.positive("size_px", 10000).value_or(s.sizePx);
    return s;
}

Shape readRect(TableReader &t)
{
    RectShape s;
    s.position = t.vec2("position").value_or(s.position);
    s.size = t.vec2("size").value_or(s.size);
    s.filled = t.boolean("filled").value_or(s.filled);
    return s;
}

// A mask's fill: a colour, or "pixelate" in blocks of block_px.
Shape readMask(TableReader &t)
{
    MaskShape s;
    bool screen = false;
    if (auto points = t.points("points", kMaxMaskPoints, {}, &screen)) {
        s.points = std::move(*points);
        if (s.points.size() < kMinMaskPoints)
            t.problem("points", "a mask needs at least " + std::to_string(kMinMaskPoints) + " points");
    }
    s.world = !screen;
    const toml::node *fill = t.node("fill");
    if (fill && fill->as_string() && fill->as_string()->get() == "pixelate")
        s.fill.reset();
    else
        s.fill = t.colour("fill").value_or(Rgba{0, 0, 0, 255});
    if (s.fill && t.has("block_px"))
        t.problem("block_px", "block_px is for fill = \"pixelate\"");
    s.blockPx = unsigned(t.integer("block_px", kMinMaskBlockPx, kMaxMaskBlockPx).value_or(s.blockPx));
    return s;
}

struct ShapeReader {
    std::string_view type;
    std::array<std::string_view, 2> required;
    Shape (*read)(TableReader &);
};

} // namespace

void readShape(TableReader &table, const std::string &type, const std::string &baseDirectory, SceneImages &images,
               Shape &out)
{
    if (type == "frustum") { // its camera may name a calibration file, relative to the config's folder
        requireKeys(table, {"camera"}, type);
        out = readFrustumShape(table, baseDirectory);
        return;
    }
    if (type == "image") {
        out = readImageShape(table, baseDirectory, images);
        return;
    }
    static const ShapeReader kReaders[] = {
        {"axes", {}, readAxes},
        {"grid", {}, readGrid},
        {"polyline", {"points"}, readPolyline},
        {"markers", {"points"}, readMarkers},
        {"box", {"size"}, readBox},
        {"arc", {"radius"}, readArc},
        {"label", {"anchor", "text"}, readLabel},
        {"horizon", {}, readHorizon},
        {"guide-lines", {}, readGuideLines},
        {"text", {"text"}, readScreenText},
        {"crosshair", {}, readCrosshair},
        {"rect", {"size"}, readRect},
        {"mask", {"points"}, readMask},
    };
    std::vector<std::string> names{"frustum", "image"};
    for (const ShapeReader &reader : kReaders) {
        if (reader.type == type) {
            requireKeys(table, reader.required, type);
            out = reader.read(table);
            return;
        }
        names.emplace_back(reader.type);
    }
    std::string message = "unknown annotation type '" + type + "'";
    if (const std::string guess = closestMatch(type, names); !guess.empty())
        message += "; did you mean '" + guess + "'?";
    table.problem("type", std::move(message));
    table.ignoreRest(); // the shape keys cannot be judged without a known type
}

} // namespace overlayd
