// SPDX-License-Identifier: Apache-2.0
// The limits of what one config may ask for, named in one place: docs/config.md "Limits" lists each with its key.
// A value over a limit is refused at its key by the loader, so check-config and run refuse it alike.
#pragma once

#include <cstddef>
#include <cstdint>

namespace overlayd {

// Counts: the first entry over the limit is refused at its own position, before anything is built from it.
inline constexpr size_t kMaxFrames = 256;          // [[frame]]
inline constexpr size_t kMaxAnnotations = 1024;    // [[annotation]]
inline constexpr size_t kMaxSinks = 16;            // [[sink]]
inline constexpr size_t kMaxDashEntries = 16;      // style.dash
inline constexpr size_t kMaxDistanceMarks = 32;    // guide-lines distance_marks
inline constexpr size_t kMaxColours = 16;          // any list of colours
inline constexpr size_t kMaxFixedListEntries = 16; // lists of numbers with a fixed meaning (window, distortion)

// Lengths in bytes.
inline constexpr size_t kMaxAnnotationTextBytes = 1024; // a label's or a text annotation's text
inline constexpr size_t kMaxNameBytes = 256;            // names of annotations, frames, layers

// Image annotations: each file, and what all of a scene's image annotations decode to together (4 images of 4096 x
// 4096 RGBA; a file named by several annotations is decoded once but counts for each, as each is drawn from it).
inline constexpr size_t kMaxImageFileBytes = 16u << 20; // an image annotation's file
inline constexpr unsigned kMaxImageSide = 4096;         // its width and height, from the header
inline constexpr size_t kMaxSceneImageBytes = 256u << 20;

// Numbers with a range of their own (every other number: kMaxMagnitude in base/number_range.h).
inline constexpr double kMaxFar = 1e9;                  // camera.far, metres ("inf" where the model allows it)
inline constexpr double kMinFovDeg = 0.01;              // camera.fov, degrees: the narrowest telescope; below, the
                                                        // focal length is no longer a number (inf at 1e-300)
inline constexpr double kMinScale = 1e-6;               // |frame.scale| per axis
inline constexpr double kMaxViewportCoordinate = 65536; // viewport window/scissor x, y, width, height (pixels)
inline constexpr double kMaxCanValue = 1e15;        // input.can scale, offset, min, max, step: a 64-bit signal's values
inline constexpr double kMinStatsIntervalSec = 0.1; // daemon.stats_interval, when not 0 (off): below, it pins a core
// Recordings' segment and retention limits are stream/record_options.h's.
// A frame's transform composed from the world may not hold an entry beyond this: the chain of scales and
// translations stays finite and keeps the precision a projection needs.
inline constexpr double kMaxComposedMagnitude = 1e9;

} // namespace overlayd
