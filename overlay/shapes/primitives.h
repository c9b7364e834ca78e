// SPDX-License-Identifier: Apache-2.0
// Projected 2D primitives: what an annotation becomes after projection, in top-left (memory order) pixel coordinates.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "media/rgba.h"
#include "projection/polylines.h"

namespace overlayd {

struct StrokeStyle {
    Rgba colour{};
    double width = 2.0;
    std::vector<double> dash{};
    bool antialias = true;
};

// Polylines drawn with one style: their coverage is united before the colour is applied, so that a
// semi-transparent grid does not darken where its own lines cross.
struct StrokeItem {
    StrokeStyle style;
    Polylines lines;
};

// A filled rectangle of whole pixels [x0, x1) x [y0, y1).
struct FillItem {
    Rgba colour{};
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

// Which column of a text's box its anchor gives: the first (Left), the middle, or the last (Right).
enum class TextAlign { Left, Centre, Right };

// Text placed by one corner of its box (ascent + descent): the top-left corner, or the bottom-left one when
// anchorAtBottom (a bottom-left viewport origin puts text above its anchor, like everything else); `align` moves
// the box left of the anchor by none, half or all of its width.
struct TextItem {
    std::string text;
    glm::dvec2 anchor{0.0};
    bool anchorAtBottom = false;
    double sizePx = 16.0;
    Rgba colour{};
    std::optional<Rgba> background{};
    bool antialias = true;
    TextAlign align = TextAlign::Left;
};

// One annotation's primitives; drawn fills first, then strokes, then text.
struct DrawList {
    std::vector<FillItem> fills;
    std::vector<StrokeItem> strokes;
    std::vector<TextItem> texts;

    void clear()
    {
        fills.clear();
        strokes.clear();
        texts.clear();
    }
    bool empty() const { return fills.empty() && strokes.empty() && texts.empty(); }
};

} // namespace overlayd
