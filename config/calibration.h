// Calibration import: OpenCV calibration files (YAML/XML through cv::FileStorage) and ROS camera_info YAML.
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "base/result.h"
#include "projection/distortion.h"
#include "projection/projection.h"

namespace overlayd {

struct Calibration {
    PinholeIntrinsics pinhole{}; // fx, fy, cx, cy, skew and the image size they refer to
    Distortion distortion{};
};

// Reads `path`: .xml, or YAML starting with OpenCV's "%YAML:1.0" header, through cv::FileStorage (camera_matrix,
// distortion_coefficients, image_width, image_height, optional distortion_model); other YAML as ROS camera_info
// (image_width, image_height, camera_matrix, distortion_model, distortion_coefficients). NotFound for a missing
// file, Malformed (naming the file and the field) for anything that does not parse. Never throws.
Result<Calibration> loadCalibration(const std::string &path);

// Shared by both readers: checks a row-major 3x3 camera matrix and picks the distortion model. `model` is a ROS
// name (plumb_bob | rational_polynomial | equidistant, also fisheye) or empty to infer it from the count.
Result<Calibration> makeCalibration(const std::string &path, const std::array<double, 9> &cameraMatrix,
                                    const std::vector<double> &coefficients, std::string_view model, int width,
                                    int height);

namespace detail {
Result<Calibration> loadOpenCvCalibration(const std::string &path);
Result<Calibration> loadRosCalibration(const std::string &path);
} // namespace detail

} // namespace overlayd
