// SPDX-License-Identifier: Apache-2.0
// type = "image": the file is decoded at load time by SceneImages (check-config decodes it too, so a file run would
// refuse is refused there); here, where and how large it is drawn.
#include "config/config_sections.h"

#include <string>

#include "config/scene_images.h"

namespace overlayd {

Shape readImageShape(TableReader &table, const std::string &baseDirectory, SceneImages &images)
{
    ImageShape s;
    if (auto path = table.string("path"); path && !path->empty())
        s.image = images.load(table, resolvePath(baseDirectory, *path));
    else if (path)
        table.problem("path", "an empty path");
    else
        table.problem("path", "missing: the PNG or JPEG file, relative to the config's folder");
    s.position = table.vec2("position");
    s.sizePx = table.vec2("size_px");
    s.anchor = table.vec3("anchor");
    if (s.position.has_value() == s.anchor.has_value())
        table.problem(s.position ? "anchor" : "position",
                      "an image needs either position = [x, y] (screen pixels) or anchor = [x, y, z] (world metres), "
                      "not both");
    if (auto size = table.vec2("size")) {
        s.size = *size;
        if (!(size->x > 0 && size->y > 0))
            table.problem("size", "width and height in metres must be > 0");
    } else if (s.anchor) {
        table.problem("size", "missing: [width, height] in metres on the world plane");
    }
    if (s.sizePx && !(s.sizePx->x > 0 && s.sizePx->y > 0))
        table.problem("size_px", "width and height in pixels must be > 0");
    if (s.position && table.has("size"))
        table.problem("size", "a screen image is sized by size_px");
    if (s.anchor && table.has("size_px"))
        table.problem("size_px", "a world image is sized by size (metres)");
    s.axisU = table.vec3("axis_u").value_or(s.axisU);
    s.axisV = table.vec3("axis_v").value_or(s.axisV);
    if (glm::length(glm::cross(s.axisU, s.axisV)) < 1e-9)
        table.problem(table.has("axis_v") ? "axis_v" : "axis_u", "axis_u and axis_v must be non-zero and not parallel");
    s.opacity = table.number("opacity", 0.0, 1.0).value_or(s.opacity);
    return s;
}

} // namespace overlayd
