// ROS camera_info YAML (camera_calibration's output), read with yaml-cpp: cv::FileStorage needs OpenCV's header.
#include "config/calibration.h"

#include <yaml-cpp/yaml.h>

namespace overlayd::detail {

namespace {

Error malformed(const std::string &path, const std::string &what)
{
    return makeError(ErrorCode::Malformed, "calibration file '" + path + "': " + what);
}

// A ROS matrix: {rows, cols, data: [...]}, row-major.
std::vector<double> matrixData(const YAML::Node &node)
{
    const YAML::Node data = node["data"];
    if (!data || !data.IsSequence())
        return {};
    return data.as<std::vector<double>>();
}

Result<Calibration> read(const std::string &path, const YAML::Node &root)
{
    if (!root.IsMap())
        return malformed(path, "not a YAML mapping");
    if (!root["camera_matrix"])
        return malformed(path, "no camera_matrix");
    const std::vector<double> k = matrixData(root["camera_matrix"]);
    if (k.size() != 9)
        return malformed(path, "camera_matrix.data must hold 9 numbers");
    std::array<double, 9> matrix{};
    std::copy(k.begin(), k.end(), matrix.begin());
    std::vector<double> coefficients;
    if (root["distortion_coefficients"])
        coefficients = matrixData(root["distortion_coefficients"]);
    if (!root["image_width"] || !root["image_height"])
        return malformed(path, "image_width and image_height are required");
    const std::string model = root["distortion_model"] ? root["distortion_model"].as<std::string>() : "";
    return makeCalibration(path, matrix, coefficients, model, root["image_width"].as<int>(),
                           root["image_height"].as<int>());
}

} // namespace

Result<Calibration> loadRosCalibration(const std::string &path)
{
    // yaml-cpp throws on syntax errors and on values of the wrong type; nothing may escape the loader.
    try {
        return read(path, YAML::LoadFile(path));
    } catch (const YAML::Exception &e) {
        return malformed(path, "does not parse (line " + std::to_string(e.mark.line + 1) + ": " + e.msg + ")");
    }
}

} // namespace overlayd::detail
