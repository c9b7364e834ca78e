// OpenCV calibration files (what calibrateCamera samples write), read through cv::FileStorage.
#include "config/calibration.h"

#include <opencv2/core.hpp>

namespace overlayd::detail {

namespace {

Error malformed(const std::string &path, const std::string &what)
{
    return makeError(ErrorCode::Malformed, "calibration file '" + path + "': " + what);
}

Result<Calibration> read(const std::string &path, cv::FileStorage &fs)
{
    cv::Mat k, d;
    fs["camera_matrix"] >> k;
    if (k.empty())
        return malformed(path, "no camera_matrix");
    if (k.rows != 3 || k.cols != 3)
        return malformed(path, "camera_matrix must be 3x3");
    k.convertTo(k, CV_64F);
    std::array<double, 9> matrix{};
    for (int i = 0; i < 9; ++i)
        matrix[size_t(i)] = k.at<double>(i / 3, i % 3);
    fs["distortion_coefficients"] >> d;
    std::vector<double> coefficients;
    if (!d.empty()) {
        if (d.rows != 1 && d.cols != 1)
            return malformed(path, "distortion_coefficients must be a vector");
        d.convertTo(d, CV_64F);
        coefficients.assign(d.begin<double>(), d.end<double>());
    }
    const cv::FileNode width = fs["image_width"], height = fs["image_height"];
    if (!width.isInt() || !height.isInt())
        return malformed(path, "image_width and image_height must be integers");
    std::string model;
    if (const cv::FileNode node = fs["distortion_model"]; node.isString())
        model = std::string(node);
    return makeCalibration(path, matrix, coefficients, model, int(width), int(height));
}

} // namespace

Result<Calibration> loadOpenCvCalibration(const std::string &path)
{
    // cv::FileStorage throws cv::Exception on syntax errors; nothing may escape the loader.
    try {
        cv::FileStorage fs(path, cv::FileStorage::READ);
        if (!fs.isOpened())
            return malformed(path, "cv::FileStorage cannot open it");
        return read(path, fs);
    } catch (const cv::Exception &e) {
        return malformed(path, "does not parse (" + e.msg + ")");
    }
}

} // namespace overlayd::detail
