// SPDX-License-Identifier: Apache-2.0
// Calibration import: OpenCV calibration files (XML through tinyxml2, YAML through yaml-cpp) and ROS camera_info YAML.
#pragma once

#include <array>
#include <optional>
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

// A calibration file is a few hundred bytes; anything near this is not one.
inline constexpr size_t kMaxCalibrationFileBytes = 1u << 20;
// Distortion coefficient counts OpenCV's calibrateCamera writes (k1 k2 p1 p2 [k3 [k4 k5 k6 [s1..s4 [tx ty]]]]).
inline constexpr size_t kOpenCvCoefficientCounts[] = {4, 5, 8, 12, 14};
inline constexpr size_t kMaxCoefficients = 14;

// Reads `path`: .xml, or YAML starting with OpenCV's "%YAML:1.0" header, as OpenCV writes them (camera_matrix,
// distortion_coefficients, image_width, image_height, optional distortion_model); other YAML as ROS camera_info
// (image_width, image_height, camera_matrix, distortion_model, distortion_coefficients). The file must be a regular
// file of at most kMaxCalibrationFileBytes, nest at most kMaxNestingDepth levels and name no key twice in a
// mapping; each matrix's declared size is checked against what the field needs before its data is read. NotFound
// for a missing file, Malformed (naming the file, the line where it can and the field) for anything that does not
// parse, InvalidArgument or Io (naming the file) for what is not a calibration file at all. Never throws.
Result<Calibration> loadCalibration(const std::string &path);
// The same for a file's text already read (the fuzz target); `path` names it in messages and its extension (.xml)
// picks the reader as the content does.
Result<Calibration> loadCalibrationText(const std::string &path, const std::string &text);

// Shared by both readers: checks a row-major 3x3 camera matrix and picks the distortion model. `model` is a ROS
// name (plumb_bob | rational_polynomial | equidistant, also fisheye) or empty to infer it from the count.
Result<Calibration> makeCalibration(const std::string &path, const std::array<double, 9> &cameraMatrix,
                                    const std::vector<double> &coefficients, std::string_view model, int width,
                                    int height);

// `text` is the file's content, already checked for size and depth. OpenCV's XML goes through tinyxml2, YAML
// (OpenCV's %YAML:1.0 and ROS's) through yaml-cpp: both give every refusal its line, and neither loops forever
// or crashes on malformed files as cv::FileStorage's parsers did (found by tests/fuzz/calibration_fuzz).
Result<Calibration> loadOpenCvXmlCalibration(const std::string &path, const std::string &text);
Result<Calibration> loadYamlCalibration(const std::string &path, const std::string &text, bool openCv);

// What an opencv-matrix declares, as either parser saw it, before its data is read.
struct DeclaredMatrix {
    bool isMap = false;
    std::optional<long long> rows, cols; // nullopt when not an integer
    std::optional<std::string> dt;       // nullopt when not a string
    std::optional<size_t> count;         // entries in data; nullopt when data is not a list
};
// What is wrong with the matrix declared for `field` ("camera_matrix": 3x3; "distortion_coefficients": 1xN or
// Nx1, N one of kOpenCvCoefficientCounts; one channel; data rows x cols long), "" when nothing.
std::string openCvMatrixProblem(const std::string &field, const DeclaredMatrix &matrix);

// "calibration file PATH: what", and "calibration file PATH:LINE: what" when line (1-based) is known.
Error calibrationError(const std::string &path, const std::string &what, unsigned line = 0);

} // namespace overlayd
