// SPDX-License-Identifier: Apache-2.0
// Shared set-up of the renderer tests: a camera looking down at a ground plane, a demo scene, stream formats.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "overlay/scene_renderer.h"
#include "overlay/shapes/annotation.h"
#include "projection/camera.h"
#include "test_frames.h"

namespace overlayd::test {

// A pinhole camera (fx = fy = 0.8 * width) 2 m above the ground at x = -4, looking along +X, pitched down 25
// degrees: the world origin is in view, below the image centre.
Camera groundCamera(unsigned width, unsigned height, Origin origin = Origin::TopLeft,
                    const Distortion &distortion = Distortion{});

// Ground grid, axes, a box, guide lines, markers; with text: a label and a screen text with a token.
OverlayScene demoScene(bool withText);

StreamFormat streamFormat(const std::string &formatName, unsigned width, unsigned height);

// A frame of one grey (RGB 110, 120, 130 in BT.601 limited range) with padded strides.
TestFrame greyFrame(const std::string &formatName, unsigned width, unsigned height, unsigned stridePadding);

// Every pixel format's name, and the test name a format parameter gets (for INSTANTIATE_TEST_SUITE_P).
std::vector<std::string> formatNames();
std::string formatName(const testing::TestParamInfo<std::string> &param);

std::unique_ptr<SceneRenderer> makeRenderer(const OverlayScene &scene, const Camera &camera,
                                            const StreamFormat &format);

// Alpha channel of a layer as CV_8UC1.
cv::Mat layerAlpha(const OverlayLayer &layer);

Annotation annotation(const std::string &name, Shape shape, Rgba colour = kWhite, double width = 2.0,
                      const std::string &layer = "default");

} // namespace overlayd::test
