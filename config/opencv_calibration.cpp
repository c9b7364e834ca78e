// OpenCV calibration files (what calibrateCamera samples write), read through cv::FileStorage. Matrices are read
// field by field rather than with `>> cv::Mat`, which allocates whatever rows x cols the file declares before it
// looks at the data: the declared size is checked against what the field needs first.
#include "config/calibration.h"

#include <algorithm>
#include <set>

#include <opencv2/core.hpp>

namespace overlayd::detail {

namespace {

// cv::FileNode knows no line numbers: the line of the nth occurrence of `key` as a YAML key ("key:") or an XML
// element ("<key>", "<key "), found in the text. 0 when it is not found.
unsigned lineOfKey(const std::string &text, const std::string &key, int occurrence = 1)
{
    unsigned line = 1;
    for (size_t start = 0; start < text.size(); ++line) {
        const size_t end = std::min(text.find('\n', start), text.size());
        const std::string_view row = std::string_view(text).substr(start, end - start);
        const size_t first = row.find_first_not_of(" \t");
        if (first != std::string_view::npos) {
            const std::string_view token = row.substr(first);
            if ((token.starts_with(key + ":") || token.starts_with("<" + key + ">") ||
                 token.starts_with("<" + key + " ")) &&
                --occurrence == 0)
                return line;
        }
        start = end + 1;
    }
    return 0;
}

class Reader
{
public:
    Reader(const std::string &path, const std::string &text) : path_(path), text_(text) {}

    Error error(const std::string &key, const std::string &what, int occurrence = 1) const
    {
        return calibrationError(path_, key + ": " + what, lineOfKey(text_, key, occurrence));
    }

    // A key given twice in one mapping: cv::FileStorage keeps both and answers with the first.
    Status checkDuplicates(const cv::FileNode &map) const
    {
        std::set<std::string> seen;
        for (auto it = map.begin(); it != map.end(); ++it) {
            const cv::FileNode node = *it;
            if (!seen.insert(node.name()).second)
                return error(node.name(), "given twice in one mapping", 2);
            if (node.isMap())
                if (auto nested = checkDuplicates(node); !nested)
                    return nested; // depth is bounded by the pre-scan
        }
        return Ok{};
    }

    // An opencv-matrix {rows, cols, dt, data} whose size `fits`, read row-major as doubles.
    template<typename Fits>
    Result<std::vector<double>> matrix(const cv::FileNode &root, const std::string &key, Fits fits,
                                       const std::string &needed) const
    {
        const cv::FileNode node = root[key];
        if (!node.isMap())
            return error(key, "not an opencv-matrix (rows, cols, dt, data)");
        const cv::FileNode rows = node["rows"], cols = node["cols"], dt = node["dt"], data = node["data"];
        if (!rows.isInt() || !cols.isInt())
            return error(key, "rows and cols must be integers");
        if (!fits(int(rows), int(cols)))
            return error(key, std::to_string(int(rows)) + "x" + std::to_string(int(cols)) + "; " + needed);
        // One letter is one channel; "2d", "3f" ... interleave channels that a calibration does not have.
        if (!dt.isString() || std::string(dt).size() != 1 ||
            std::string("ucwsifdh").find(std::string(dt)) == std::string::npos)
            return error(key, "dt must be one single-channel type (u, c, w, s, i, f, d, h), got '" +
                                  (dt.isString() ? std::string(dt) : std::string()) + "'");
        const size_t count = size_t(int(rows)) * size_t(int(cols));
        if (!data.isSeq() || data.size() != count)
            return error(key, "data must hold rows x cols = " + std::to_string(count) + " numbers, got " +
                                  std::to_string(data.isSeq() ? data.size() : 0));
        std::vector<double> values;
        for (auto it = data.begin(); it != data.end(); ++it) {
            if (!(*it).isReal() && !(*it).isInt())
                return error(key, "data holds something that is not a number");
            values.push_back(double(*it));
        }
        return values;
    }

    Result<Calibration> read(const cv::FileStorage &fs) const
    {
        if (auto unique = checkDuplicates(fs.root()); !unique)
            return unique.error();
        if (fs["camera_matrix"].empty())
            return calibrationError(path_, "no camera_matrix");
        auto k = matrix(
            fs.root(), "camera_matrix", [](int r, int c) { return r == 3 && c == 3; }, "it must be 3x3");
        if (!k)
            return k.error();
        std::array<double, 9> camera{};
        std::copy(k->begin(), k->end(), camera.begin());
        std::vector<double> coefficients;
        if (!fs["distortion_coefficients"].empty()) {
            const auto counted = [](int r, int c) {
                const auto &counts = kOpenCvCoefficientCounts;
                const int n = r == 1 ? c : c == 1 ? r : 0;
                return std::find(std::begin(counts), std::end(counts), size_t(std::max(n, 0))) != std::end(counts);
            };
            auto d = matrix(fs.root(), "distortion_coefficients", counted,
                            "it must be 1xN or Nx1 with N = 4, 5, 8, 12 or 14");
            if (!d)
                return d.error();
            coefficients = std::move(*d);
        }
        const cv::FileNode width = fs["image_width"], height = fs["image_height"];
        if (!width.isInt() || !height.isInt())
            return calibrationError(path_, "image_width and image_height must be integers");
        std::string model;
        if (const cv::FileNode node = fs["distortion_model"]; node.isString())
            model = std::string(node);
        return makeCalibration(path_, camera, coefficients, model, int(width), int(height));
    }

private:
    const std::string &path_;
    const std::string &text_;
};

} // namespace

Result<Calibration> loadOpenCvCalibration(const std::string &path, const std::string &text)
{
    // cv::FileStorage throws cv::Exception on syntax errors, and std::length_error on some (a key that is empty, as
    // "   : 1280" in a mapping is); nothing may escape the loader.
    try {
        cv::FileStorage fs(text, cv::FileStorage::READ | cv::FileStorage::MEMORY);
        if (!fs.isOpened())
            return calibrationError(path, "cv::FileStorage cannot read it");
        return Reader(path, text).read(fs);
    } catch (const cv::Exception &e) {
        return calibrationError(path, "does not parse (" + e.msg + ")");
    } catch (const std::exception &e) {
        return calibrationError(path, std::string("does not parse (") + e.what() + ")");
    }
}

} // namespace overlayd::detail
