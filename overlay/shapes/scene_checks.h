// SPDX-License-Identifier: Apache-2.0
// Configure-time validation of an overlay scene: every problem is found before anything is drawn.
#pragma once

#include <optional>
#include <string>

#include "base/result.h"
#include "overlay/shapes/annotation.h"
#include "projection/scene_graph.h"

namespace overlayd {

// What is wrong with one annotation: `key` is the annotation's key it is about ("size", "style.dash").
struct AnnotationProblem {
    std::string key;
    std::string message;
};

// The first problem of one annotation's own numbers, sizes, dash pattern and text tokens, or nullopt. The config
// loader reports it at the key (so that check-config refuses what the renderer would); checkScene below runs it too.
std::optional<AnnotationProblem> checkAnnotation(const Annotation &annotation);

// Unknown frames, non-finite numbers, non-positive widths and sizes, bad dash patterns and text tokens; the
// message names the annotation.
Status checkScene(const OverlayScene &scene, const SceneGraph &graph);
// The text slots the scene's screen texts show ({slot:NAME}), in the order they first appear.
std::vector<std::string> textSlotNames(const OverlayScene &scene);

} // namespace overlayd
