// SPDX-License-Identifier: Apache-2.0
// Calibration YAML read with yaml-cpp: ROS camera_info (camera_calibration's output) and OpenCV's own (%YAML:1.0,
// !!opencv-matrix), whose header line yaml-cpp does not know and sees as a comment. Not cv::FileStorage for the
// latter: its YAML parser loops forever on some malformed files (found by tests/fuzz/calibration_fuzz) and knows no
// line numbers. Every refusal names the line (yaml-cpp's marks count from 0).
#include "config/calibration.h"

#include <map>

#include <yaml-cpp/yaml.h>

namespace overlayd {

namespace {

unsigned lineOf(const YAML::Node &node)
{
    return node.Mark().line >= 0 ? unsigned(node.Mark().line + 1) : 0;
}

class Reader
{
public:
    Reader(const std::string &path, bool openCv) : path_(path), openCv_(openCv) {}

    Error error(const YAML::Node &at, const std::string &what) const
    {
        return calibrationError(path_, what, lineOf(at));
    }

    // yaml-cpp keeps both entries of a key given twice and answers with the first: refused, in every mapping.
    Status checkDuplicates(const YAML::Node &node) const
    {
        if (node.IsSequence())
            for (const YAML::Node &item : node)
                if (auto nested = checkDuplicates(item); !nested)
                    return nested; // depth is bounded by the pre-scan
        if (!node.IsMap())
            return Ok{};
        std::map<std::string, unsigned> seen;
        for (const auto &entry : node) {
            const std::string key = entry.first.IsScalar() ? entry.first.Scalar() : "";
            if (const auto [it, fresh] = seen.emplace(key, lineOf(entry.first)); !fresh)
                return error(entry.first,
                             "'" + key + "' given twice (first on line " + std::to_string(it->second) + ")");
            if (auto nested = checkDuplicates(entry.second); !nested)
                return nested;
        }
        return Ok{};
    }

    Result<std::vector<double>> numbers(const YAML::Node &data, const std::string &key) const
    {
        std::vector<double> values;
        for (const YAML::Node &value : data) {
            if (!value.IsScalar())
                return error(value, key + ".data: expected a list of numbers");
            values.push_back(value.as<double>());
        }
        return values;
    }

    // A ROS matrix: {rows, cols, data: [...]}, row-major; rows and cols, when given, must agree with the data.
    Result<std::vector<double>> rosMatrix(const YAML::Node &root, const std::string &key) const
    {
        const YAML::Node node = root[key];
        if (!node.IsMap())
            return error(node, key + ": expected {rows, cols, data: [...]}");
        const YAML::Node data = node["data"];
        if (!data || !data.IsSequence())
            return error(data ? data : node, key + ".data: expected a list of numbers");
        auto values = numbers(data, key);
        const YAML::Node rows = node["rows"], cols = node["cols"];
        if (values && rows && cols && size_t(rows.as<int>()) * size_t(cols.as<int>()) != values->size())
            return error(rows, key + ": rows x cols = " + rows.Scalar() + "x" + cols.Scalar() + ", but data holds " +
                                   std::to_string(values->size()) + " numbers");
        return values;
    }

    // An !!opencv-matrix {rows, cols, dt, data}: the declaration is checked before the data is read.
    Result<std::vector<double>> openCvMatrix(const YAML::Node &root, const std::string &key) const
    {
        const YAML::Node node = root[key];
        DeclaredMatrix declared;
        declared.isMap = node.IsMap();
        if (declared.isMap) {
            const YAML::Node rows = node["rows"], cols = node["cols"], dt = node["dt"], data = node["data"];
            long long r = 0, c = 0;
            if (rows && cols && YAML::convert<long long>::decode(rows, r) && YAML::convert<long long>::decode(cols, c))
                declared.rows = r, declared.cols = c;
            if (dt && dt.IsScalar())
                declared.dt = dt.Scalar();
            if (data && data.IsSequence())
                declared.count = data.size();
        }
        if (const std::string problem = openCvMatrixProblem(key, declared); !problem.empty())
            return calibrationError(path_, key + ": " + problem, keyLine(root, key));
        return numbers(node["data"], key);
    }

    Result<std::vector<double>> matrix(const YAML::Node &root, const std::string &key) const
    {
        return openCv_ ? openCvMatrix(root, key) : rosMatrix(root, key);
    }

    static unsigned keyLine(const YAML::Node &map, const std::string &key)
    {
        for (const auto &entry : map)
            if (entry.first.IsScalar() && entry.first.Scalar() == key)
                return lineOf(entry.first);
        return 0;
    }

    Result<Calibration> read(const YAML::Node &root) const
    {
        if (!root.IsMap())
            return calibrationError(path_, "not a YAML mapping");
        if (auto unique = checkDuplicates(root); !unique)
            return unique.error();
        if (!root["camera_matrix"])
            return calibrationError(path_, "no camera_matrix");
        auto k = matrix(root, "camera_matrix");
        if (!k)
            return k.error();
        if (k->size() != 9)
            return error(root["camera_matrix"]["data"],
                         "camera_matrix.data must hold 9 numbers (3x3), got " + std::to_string(k->size()));
        std::array<double, 9> camera{};
        std::copy(k->begin(), k->end(), camera.begin());
        std::vector<double> coefficients;
        if (root["distortion_coefficients"]) {
            auto d = matrix(root, "distortion_coefficients");
            if (!d)
                return d.error();
            if (d->size() > kMaxCoefficients) // OpenCV's were checked against kOpenCvCoefficientCounts
                return error(root["distortion_coefficients"]["data"],
                             "distortion_coefficients.data holds " + std::to_string(d->size()) + " numbers; at most " +
                                 std::to_string(kMaxCoefficients));
            coefficients = std::move(*d);
        }
        if (!root["image_width"] || !root["image_height"])
            return calibrationError(path_, "image_width and image_height are required");
        const std::string model = root["distortion_model"] ? root["distortion_model"].as<std::string>() : "";
        return makeCalibration(path_, camera, coefficients, model, root["image_width"].as<int>(),
                               root["image_height"].as<int>());
    }

private:
    const std::string &path_;
    bool openCv_;
};

} // namespace

Result<Calibration> loadYamlCalibration(const std::string &path, const std::string &text, bool openCv)
{
    // "%YAML:1.0" is OpenCV's spelling; as a comment of the same length every line keeps its number.
    std::string yaml = text;
    if (openCv)
        yaml[0] = '#';
    // yaml-cpp throws on syntax errors and on values of the wrong type; nothing may escape the loader.
    try {
        return Reader(path, openCv).read(YAML::Load(yaml));
    } catch (const YAML::Exception &e) {
        return calibrationError(path, "does not parse (" + e.msg + ")", unsigned(e.mark.line + 1));
    } catch (const std::exception &e) { // from the standard library underneath (bad_alloc, length_error)
        return calibrationError(path, std::string("does not parse (") + e.what() + ")");
    }
}

} // namespace overlayd
