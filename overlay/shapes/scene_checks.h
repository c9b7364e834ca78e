// Configure-time validation of an overlay scene: every problem is found before anything is drawn.
#pragma once

#include "base/result.h"
#include "overlay/shapes/annotation.h"
#include "projection/scene_graph.h"

namespace overlayd {

// Unknown frames, non-finite numbers, non-positive widths and sizes, bad dash patterns and text tokens; the
// message names the annotation.
Status checkScene(const OverlayScene &scene, const SceneGraph &graph);
// The text slots the scene's screen texts show ({slot:NAME}), in the order they first appear.
std::vector<std::string> textSlotNames(const OverlayScene &scene);

} // namespace overlayd
