// SPDX-License-Identifier: Apache-2.0
// Calibration import: picks the reader for a file and turns its camera matrix and coefficients into our types.
#include "config/calibration.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "base/regular_file.h"
#include "config/nesting_depth.h"

namespace overlayd {

Error calibrationError(const std::string &path, const std::string &what, unsigned line)
{
    return makeError(ErrorCode::Malformed,
                     "calibration file " + path + (line > 0 ? ":" + std::to_string(line) : "") + ": " + what);
}

std::string openCvMatrixProblem(const std::string &field, const DeclaredMatrix &matrix)
{
    if (!matrix.isMap)
        return "not an opencv-matrix (rows, cols, dt, data)";
    if (!matrix.rows || !matrix.cols)
        return "rows and cols must be integers";
    const long long rows = *matrix.rows, cols = *matrix.cols;
    const std::string size = std::to_string(rows) + "x" + std::to_string(cols);
    if (field == "camera_matrix" && (rows != 3 || cols != 3))
        return size + "; it must be 3x3";
    const long long n = rows == 1 ? cols : cols == 1 ? rows : 0;
    if (field != "camera_matrix" && std::find(std::begin(kOpenCvCoefficientCounts), std::end(kOpenCvCoefficientCounts),
                                              size_t(std::max(n, 0LL))) == std::end(kOpenCvCoefficientCounts))
        return size + "; it must be 1xN or Nx1 with N = 4, 5, 8, 12 or 14";
    // One letter is one channel; "2d", "3f" ... interleave channels that a calibration does not have.
    if (!matrix.dt || matrix.dt->size() != 1 || std::string_view("ucwsifdh").find(*matrix.dt) == std::string::npos)
        return "dt must be one single-channel type (u, c, w, s, i, f, d, h), got '" + matrix.dt.value_or("") + "'";
    if (matrix.count != size_t(rows * cols))
        return "data must hold rows x cols = " + std::to_string(rows * cols) + " numbers, got " +
               std::to_string(matrix.count.value_or(0));
    return {};
}

namespace {

Error malformed(const std::string &path, const std::string &what)
{
    return calibrationError(path, what);
}

Result<DistortionModel> pickModel(const std::string &path, std::string_view model, size_t count)
{
    if (model == "plumb_bob" || model == "radtan")
        return DistortionModel::RadialTangential;
    if (model == "rational_polynomial" || model == "rational")
        return DistortionModel::Rational;
    if (model == "equidistant" || model == "fisheye")
        return DistortionModel::Fisheye;
    if (!model.empty())
        return malformed(path, "unknown distortion_model '" + std::string(model) +
                                   "' (expected plumb_bob | rational_polynomial | equidistant)");
    // OpenCV's calibrateCamera writes 4, 5, 8, 12 or 14 coefficients; 4 means k1 k2 p1 p2 there.
    if (count == 0)
        return DistortionModel::None;
    return count <= 5 ? DistortionModel::RadialTangential : DistortionModel::Rational;
}

} // namespace

Result<Calibration> makeCalibration(const std::string &path, const std::array<double, 9> &k,
                                    const std::vector<double> &coefficients, std::string_view model, int width,
                                    int height)
{
    for (double value : k)
        if (!std::isfinite(value))
            return malformed(path, "camera_matrix has a non-finite entry");
    if (k[3] != 0.0 || k[6] != 0.0 || k[7] != 0.0 || k[8] != 1.0)
        return malformed(path, "camera_matrix must be [fx skew cx; 0 fy cy; 0 0 1]");
    if (width <= 0 || height <= 0 || width > 65536 || height > 65536)
        return malformed(path, "image_width/image_height missing or out of range (got " + std::to_string(width) + "x" +
                                   std::to_string(height) + ")");
    auto picked = pickModel(path, model, coefficients.size());
    if (!picked)
        return picked.error();
    Calibration out;
    out.pinhole = PinholeIntrinsics{k[0], k[4], k[2], k[5], k[1], width, height};
    out.distortion.model = *picked;
    const size_t used = size_t(coefficientCount(*picked));
    for (size_t i = 0; i < coefficients.size(); ++i) {
        if (!std::isfinite(coefficients[i]))
            return malformed(path, "distortion_coefficients has a non-finite entry");
        if (i < used)
            out.distortion.coeffs[i] = coefficients[i];
        else if (coefficients[i] != 0.0)
            return malformed(path, std::to_string(coefficients.size()) +
                                       " distortion coefficients, but the model takes " + std::to_string(used) +
                                       " (thin-prism and tilt terms are not supported)");
    }
    if (auto status = validateDistortion(out.distortion); !status)
        return malformed(path, status.error().message);
    return out;
}

Result<Calibration> loadCalibrationText(const std::string &path, const std::string &text)
{
    // cv::FileStorage reads the text as C strings and crashes (SIGSEGV) on a NUL byte in an XML file.
    if (const size_t nul = text.find('\0'); nul != std::string::npos)
        return calibrationError(path, "holds a NUL byte: not a text file",
                                unsigned(1 + std::count(text.begin(), text.begin() + long(nul), '\n')));
    const std::string extension = std::filesystem::path(path).extension().string();
    // The content decides first: OpenCV's YAML header, then an XML declaration or the .xml name.
    const bool openCvYaml = text.starts_with("%YAML:");
    const bool xml = !openCvYaml && (extension == ".xml" || text.starts_with("<?xml"));
    // cv::FileStorage recurses once per level and overflows the stack on a few thousand; yaml-cpp stops at its own
    // limit with a message that does not say why ("bad file").
    if (auto deep = findTooDeep(text, xml ? TextSyntax::Xml : TextSyntax::Yaml))
        return calibrationError(
            path, "nested deeper than " + std::to_string(kMaxNestingDepth) + " levels (a calibration file needs 3)",
            deep->line);
    if (xml)
        return loadOpenCvXmlCalibration(path, text);
    return loadYamlCalibration(path, text, openCvYaml);
}

Result<Calibration> loadCalibration(const std::string &path)
{
    auto text = readRegularFile(path, kMaxCalibrationFileBytes);
    if (!text)
        return makeError(text.error().code, "calibration file " + path + " " + text.error().message);
    return loadCalibrationText(path, *text);
}

} // namespace overlayd
