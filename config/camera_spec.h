// SPDX-License-Identifier: Apache-2.0
// CameraSpec: the camera as configured (pose, intrinsics, distortion, viewport), resolved to a Camera once the
// stream's frame size is known (a V4L2 device may adjust the size; intrinsics then scale with it).
#pragma once

#include <optional>
#include <string>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>

#include "base/result.h"
#include "projection/camera.h"
#include "projection/distortion.h"
#include "projection/pose.h"
#include "projection/projection.h"
#include "projection/viewport.h"

namespace overlayd {

// Which of Projection's constructors the intrinsics use.
// How a stream of another aspect than the calibrated image was made from it (libcamera's ScalerCrop would describe
// it): None refuses another aspect; Center is the largest centred region of the stream's aspect, scaled uniformly;
// Region is CameraSpec::calibrationRegion, scaled to the stream (a binned mode: the whole sensor, scale 1/2).
enum class CalibrationCrop { None, Center, Region };

// A region of the calibrated image in its pixels' edge coordinates: x, y of the top-left corner, width, height.
struct CalibrationRegion {
    double x = 0, y = 0, width = 0, height = 0;

    bool operator==(const CalibrationRegion &) const = default;
};

// The pose keys a config wrote (config/pose_config.cpp): a save writes the live pose back in them, in the user's own
// units and axes, rather than in a form the user did not choose.
enum class PoseForm { LookAt, Gaze, PrpVpnVup, Orientation, YawPitchRoll, Rodrigues, Rt };

struct PoseKeysUsed {
    PoseForm form = PoseForm::Rt;
    CameraAxes axes = CameraAxes::Body; // the orientation form's `axes`
    double targetDistance = 1.0;        // look-at: how far the target was from the eye

    bool operator==(const PoseKeysUsed &) const = default;
};

enum class IntrinsicsForm {
    FieldOfView,        // fovDeg across fovAxis, aspect from the viewport window (round circles)
    Frustum,            // bounds.left..top on the near plane (glFrustum)
    Pinhole,            // calibrated fx, fy, cx, cy, skew for an image of pinhole.width x height
    Window,             // the viewing pipeline's window model
    Orthographic,       // bounds.left..top box (glOrtho)
    WindowOrthographic, // the viewing pipeline's P_o for a centred orthoSize window
};

class CameraSpec
{
public:
    // The Camera for a frame of width x height. Intrinsics given for another image size (calibration) are scaled
    // to this one; the viewport's frame size is this one.
    Result<Camera> build(unsigned frameWidth, unsigned frameHeight) const;

    // The steps of build(), separate so that the config loader can report each failure at the keys behind it.
    Result<Viewport> buildViewport(unsigned frameWidth, unsigned frameHeight) const;
    Result<Projection> buildProjection(const Viewport &viewport) const;
    // Pinhole intrinsics for the viewport window, from the image size they were calibrated at. The same aspect
    // (within a pixel): scaled, pixel centres mapping as u' = (u + 0.5) s - 0.5. Another aspect is refused unless
    // calibrationCrop says how the stream was cut from the calibrated image.
    Result<PinholeIntrinsics> scaledPinhole(const Viewport &viewport) const;
    // What scaledPinhole does to the calibration for this window, in words ("" when the sizes match), for a log.
    std::string calibrationScaling(const Viewport &viewport) const;
    // An explicit calibration_crop region against the calibrated image and this stream: inside the image, not
    // empty, and of the stream's aspect within a pixel. Ok for the other crop forms.
    Status checkCalibrationRegion(const Viewport &viewport) const;
    // World to the internal camera frame: the pose in its mount frame, after world to mount.
    glm::dmat4 view() const;

    // Filled by the config loader.
    Pose pose{}; // mount frame to camera
    std::string mountFrame = "world";
    PoseKeysUsed poseKeys{};        // the config's pose form; the API's edits keep it
    glm::dmat4 worldFromMount{1.0}; // resolved from the scene graph when loading

    IntrinsicsForm form = IntrinsicsForm::FieldOfView;
    FovAxis fovAxis = FovAxis::Vertical;
    double fovDeg = 60.0;
    FrustumBounds bounds{};      // Frustum and Orthographic: left, right, bottom, top (near/far below)
    PinholeIntrinsics pinhole{}; // width, height 0: the stream's viewport window
    CalibrationCrop calibrationCrop = CalibrationCrop::None;
    CalibrationRegion calibrationRegion{}; // for CalibrationCrop::Region
    WindowIntrinsics window{};             // focal, centre, half spans (near/far below)
    glm::dvec2 orthoSize{2.0, 2.0};
    double near = 0.1, far = 1000.0; // metres in front of the camera; far may be kInfiniteFar (perspective)
    DepthRange depth = DepthRange::MinusOneToOne;
    Distortion distortion{};
    ViewportSpec viewport{}; // frameWidth/frameHeight are set by build()

    // Every field: a reload compares whole specs, so a field added later is never ignored.
    bool operator==(const CameraSpec &) const = default;
};

} // namespace overlayd
