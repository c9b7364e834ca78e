// SPDX-License-Identifier: Apache-2.0
// OpenCV calibration files in XML (what calibrateCamera's samples write with a .xml name), read with tinyxml2. Not
// cv::FileStorage: its XML parser dereferences a null pointer on some malformed files (`<?xml versioimagn=`, found
// by tests/fuzz/calibration_fuzz) and knows no line numbers. OpenCV's XML is one <opencv_storage> element whose
// children are the keys; a scalar is an element's text, an opencv-matrix an element of <rows>, <cols>, <dt> and a
// <data> of numbers separated by white space. Every refusal names the element's line.
#include "config/calibration.h"

#include <algorithm>
#include <charconv>
#include <map>
#include <optional>
#include <string_view>

#include <tinyxml2.h>

namespace overlayd {

namespace {

using tinyxml2::XMLElement;

std::string_view trimmed(const char *text)
{
    std::string_view view = text ? text : "";
    const size_t first = view.find_first_not_of(" \t\r\n");
    if (first == std::string_view::npos)
        return {};
    return view.substr(first, view.find_last_not_of(" \t\r\n") - first + 1);
}

// An element's text when it has no child elements (a scalar), nullopt otherwise.
std::optional<std::string_view> scalar(const XMLElement *element)
{
    if (!element || element->FirstChildElement())
        return std::nullopt;
    return trimmed(element->GetText());
}

template<typename Number>
std::optional<Number> number(std::string_view token)
{
    Number value{};
    const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (token.empty() || error != std::errc() || end != token.data() + token.size())
        return std::nullopt;
    return value;
}

// An element's text as an integer, nullopt when it is not one (or has child elements).
template<typename Integer>
std::optional<Integer> integer(const XMLElement *element)
{
    const auto text = scalar(element);
    return text ? number<Integer>(*text) : std::nullopt;
}

// OpenCV writes a string in double quotes when it holds a space or a character XML would mistake.
std::string unquoted(std::string_view text)
{
    if (text.size() >= 2 && text.front() == '"' && text.back() == '"')
        text = text.substr(1, text.size() - 2);
    return std::string(text);
}

// The white-space separated tokens of a <data> element.
std::vector<std::string_view> tokens(std::string_view text)
{
    std::vector<std::string_view> out;
    for (size_t start = text.find_first_not_of(" \t\r\n"); start != std::string_view::npos;) {
        const size_t end = std::min(text.find_first_of(" \t\r\n", start), text.size());
        out.push_back(text.substr(start, end - start));
        start = text.find_first_not_of(" \t\r\n", end);
    }
    return out;
}

class Reader
{
public:
    explicit Reader(const std::string &path) : path_(path) {}

    Error error(const XMLElement *at, const std::string &what) const
    {
        return calibrationError(path_, what, at ? unsigned(std::max(at->GetLineNum(), 0)) : 0);
    }

    // tinyxml2 keeps every element of a name and FirstChildElement() answers with the first: a key given twice is
    // refused, in every mapping.
    Status checkDuplicates(const XMLElement &map) const
    {
        std::map<std::string, int, std::less<>> seen;
        for (const XMLElement *child = map.FirstChildElement(); child; child = child->NextSiblingElement()) {
            if (const auto [it, fresh] = seen.emplace(child->Name(), child->GetLineNum()); !fresh)
                return error(child,
                             "'" + it->first + "' given twice (first on line " + std::to_string(it->second) + ")");
            if (auto nested = checkDuplicates(*child); !nested)
                return nested; // depth is bounded by the pre-scan
        }
        return Ok{};
    }

    // An opencv-matrix {rows, cols, dt, data}, its declaration checked first, read row-major as doubles.
    Result<std::vector<double>> matrix(const XMLElement &root, const char *key) const
    {
        const XMLElement *node = root.FirstChildElement(key);
        DeclaredMatrix declared;
        declared.isMap = node->FirstChildElement() != nullptr;
        std::vector<std::string_view> values;
        if (declared.isMap) {
            declared.rows = integer<long long>(node->FirstChildElement("rows"));
            declared.cols = integer<long long>(node->FirstChildElement("cols"));
            if (const auto dt = scalar(node->FirstChildElement("dt")))
                declared.dt = unquoted(*dt);
            if (const auto data = scalar(node->FirstChildElement("data"))) {
                values = tokens(*data);
                declared.count = values.size();
            }
        }
        if (const std::string problem = openCvMatrixProblem(key, declared); !problem.empty())
            return error(node, std::string(key) + ": " + problem);
        std::vector<double> out;
        for (std::string_view token : values) {
            const auto value = number<double>(token);
            if (!value)
                return error(node->FirstChildElement("data"), std::string(key) + ": data holds '" +
                                                                  std::string(token.substr(0, 32)) + "', not a number");
            out.push_back(*value);
        }
        return out;
    }

    Result<int> size(const XMLElement &root, const char *key) const
    {
        const XMLElement *node = root.FirstChildElement(key);
        if (!node)
            return error(&root, std::string(key) + " is required");
        const auto value = integer<int>(node);
        if (!value)
            return error(node, std::string(key) + " must be an integer");
        return *value;
    }

    Result<Calibration> read(const XMLElement &root) const
    {
        if (auto unique = checkDuplicates(root); !unique)
            return unique.error();
        if (!root.FirstChildElement("camera_matrix"))
            return error(&root, "no camera_matrix");
        auto k = matrix(root, "camera_matrix");
        if (!k)
            return k.error();
        std::array<double, 9> camera{};
        std::copy(k->begin(), k->end(), camera.begin());
        std::vector<double> coefficients;
        if (root.FirstChildElement("distortion_coefficients")) {
            auto d = matrix(root, "distortion_coefficients");
            if (!d)
                return d.error();
            coefficients = std::move(*d);
        }
        const auto width = size(root, "image_width"), height = size(root, "image_height");
        if (!width)
            return width.error();
        if (!height)
            return height.error();
        std::string model;
        if (const XMLElement *node = root.FirstChildElement("distortion_model")) {
            const auto text = scalar(node);
            if (!text)
                return error(node, "distortion_model must be a string");
            model = unquoted(*text);
        }
        return makeCalibration(path_, camera, coefficients, model, *width, *height);
    }

private:
    const std::string &path_;
};

} // namespace

Result<Calibration> loadOpenCvXmlCalibration(const std::string &path, const std::string &text)
{
    // Entities stay as written (no DTD is read, so none expands), and tinyxml2 throws nothing.
    tinyxml2::XMLDocument document(true, tinyxml2::COLLAPSE_WHITESPACE);
    if (document.Parse(text.data(), text.size()) != tinyxml2::XML_SUCCESS)
        return calibrationError(path, std::string("does not parse as XML (") + document.ErrorName() + ")",
                                unsigned(std::max(document.ErrorLineNum(), 0)));
    const XMLElement *root = document.RootElement();
    if (!root || std::string_view(root->Name()) != "opencv_storage")
        return calibrationError(path, "not an OpenCV XML file: its root element must be <opencv_storage>",
                                root ? unsigned(std::max(root->GetLineNum(), 0)) : 0);
    try {
        return Reader(path).read(*root);
    } catch (const std::exception &e) { // from the standard library underneath (bad_alloc)
        return calibrationError(path, std::string("cannot be read (") + e.what() + ")");
    }
}

} // namespace overlayd
