// OpenCV calibration files in XML (what calibrateCamera samples write with a .xml name), read through cv::FileStorage.
// Matrices are read field by field rather than with `>> cv::Mat`, which allocates whatever rows x cols the file
// declares before it looks at the data: the declared size is checked against what the field needs first.
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

    // An opencv-matrix {rows, cols, dt, data}, its declaration checked first, read row-major as doubles.
    Result<std::vector<double>> matrix(const cv::FileNode &root, const std::string &key) const
    {
        const cv::FileNode node = root[key];
        DeclaredMatrix declared;
        declared.isMap = node.isMap();
        if (declared.isMap) {
            const cv::FileNode rows = node["rows"], cols = node["cols"], dt = node["dt"], data = node["data"];
            if (rows.isInt() && cols.isInt())
                declared.rows = int(rows), declared.cols = int(cols);
            if (dt.isString())
                declared.dt = std::string(dt);
            if (data.isSeq())
                declared.count = data.size();
        }
        if (const std::string problem = openCvMatrixProblem(key, declared); !problem.empty())
            return error(key, problem);
        std::vector<double> values;
        const cv::FileNode data = node["data"];
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
        auto k = matrix(fs.root(), "camera_matrix");
        if (!k)
            return k.error();
        std::array<double, 9> camera{};
        std::copy(k->begin(), k->end(), camera.begin());
        std::vector<double> coefficients;
        if (!fs["distortion_coefficients"].empty()) {
            auto d = matrix(fs.root(), "distortion_coefficients");
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

Result<Calibration> loadOpenCvXmlCalibration(const std::string &path, const std::string &text)
{
    // cv::FileStorage throws cv::Exception on syntax errors, and std::length_error on some (a key that is empty, as
    // "   : 1280" in a mapping is); nothing may escape the loader.
    try {
        // FORMAT_XML: never its YAML parser (it loops forever on some files), whatever the text looks like.
        cv::FileStorage fs(text, cv::FileStorage::READ | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_XML);
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
