// SPDX-License-Identifier: Apache-2.0
// [[frame]] scene-graph frames and [[annotation]] entries with their style.
#include "config/config_sections.h"

#include <algorithm>
#include <cmath>

#include "config/limits.h"
#include "config/scene_images.h"
#include "overlay/shapes/scene_checks.h"

namespace overlayd {

namespace {

std::optional<glm::dvec3> readScale(TableReader &frame)
{
    const toml::node *n = frame.node("scale");
    if (!n)
        return glm::dvec3(1.0);
    std::optional<glm::dvec3> scale;
    if (n->is_array())
        scale = frame.vec3("scale");
    else if (auto uniform = frame.number("scale"))
        scale = glm::dvec3(*uniform);
    if (scale && (std::abs(scale->x) < kMinScale || std::abs(scale->y) < kMinScale || std::abs(scale->z) < kMinScale)) {
        frame.problem("scale", "a frame's scale must not be zero on any axis (at least 1e-06 in size)");
        return std::nullopt;
    }
    return scale;
}

} // namespace

std::optional<glm::dquat> readRotation(TableReader &table, std::string_view quaternionKey)
{
    const bool angles = table.has("yaw") || table.has("pitch") || table.has("roll");
    if (table.has(quaternionKey)) {
        if (angles)
            table.problem(quaternionKey, "give the rotation as a quaternion or as yaw/pitch/roll, not both");
        return table.quaternion(quaternionKey);
    }
    const auto yaw = table.number("yaw", -360, 360), pitch = table.number("pitch", -360, 360),
               roll = table.number("roll", -360, 360);
    if ((table.has("yaw") && !yaw) || (table.has("pitch") && !pitch) || (table.has("roll") && !roll))
        return std::nullopt;
    // The same convention as poses: Rz(yaw) Ry(pitch) Rx(roll), degrees.
    return glm::angleAxis(glm::radians(yaw.value_or(0.0)), glm::dvec3(0, 0, 1)) *
           glm::angleAxis(glm::radians(pitch.value_or(0.0)), glm::dvec3(0, 1, 0)) *
           glm::angleAxis(glm::radians(roll.value_or(0.0)), glm::dvec3(1, 0, 0));
}

void readFrames(TableReader &root, std::vector<FrameSpec> &out)
{
    for (TableReader &frame : root.tables("frame", kMaxFrames)) {
        FrameSpec spec;
        if (auto name = frame.string("name", kMaxNameBytes))
            spec.name = *name;
        else if (!frame.has("name"))
            frame.problem("name", "missing: every frame needs a name");
        spec.parent = frame.string("parent", kMaxNameBytes).value_or(SceneGraph::kWorld);
        if (auto translation = frame.vec3("translation"))
            spec.transform.translation = *translation;
        if (auto rotation = readRotation(frame, "rotation"))
            spec.transform.rotation = *rotation;
        if (auto scale = readScale(frame))
            spec.transform.scale = *scale;
        frame.finish();
        out.push_back(std::move(spec));
    }
}

std::optional<Style> readStyle(TableReader &style, const Style &base)
{
    Style out = base;
    const size_t before = style.problems().size();
    if (auto colour = style.colour("colour"))
        out.colour = *colour;
    if (auto width = style.positive("width", 1000.0))
        out.width = *width;
    if (auto dash = style.numbers("dash", kMaxDashEntries, Range{0.0, 1e5})) // its period: checkAnnotation
        out.dash = *dash;
    if (auto antialias = style.boolean("antialias"))
        out.antialias = *antialias;
    if (auto layer = style.string("layer", kMaxNameBytes))
        out.layer = *layer;
    style.finish();
    return style.problems().size() == before ? std::optional(out) : std::nullopt;
}

void readAnnotations(TableReader &root, const std::string &baseDirectory, std::vector<Annotation> &out)
{
    size_t index = 0;
    SceneImages images;
    for (TableReader &table : root.tables("annotation", kMaxAnnotations)) {
        const size_t before = table.problems().size();
        Annotation annotation;
        annotation.name = table.string("name", kMaxNameBytes).value_or("annotation " + std::to_string(index++));
        if (auto frame = table.string("frame", kMaxNameBytes))
            annotation.frame = *frame;
        if (auto style = table.table("style"))
            annotation.style = readStyle(*style, Style{}).value_or(Style{});
        const auto type = table.string("type");
        if (type)
            readShape(table, *type, baseDirectory, images, annotation.shape);
        else if (!table.has("type"))
            table.problem("type", "missing: axes | grid | polyline | markers | box | arc | label | horizon | "
                                  "guide-lines | frustum | text | crosshair | rect | image | mask");
        table.finish();
        // The renderer's own rules, run here so that check-config refuses what run would, at the key; only for an
        // annotation read without problems (a refused value was left at its default, and one report is enough), and
        // not for an image after the one that took the scene past its images' total (that one was reported).
        const auto *image = std::get_if<ImageShape>(&annotation.shape);
        if (table.problems().size() == before && !(image && images.full()))
            if (const auto problem = checkAnnotation(annotation))
                table.problemAtPath(problem->key, problem->message);
        out.push_back(std::move(annotation));
    }
}

} // namespace overlayd
