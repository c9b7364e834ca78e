// SPDX-License-Identifier: Apache-2.0
// parsePointsJson: nlohmann::json parses; a scan of the text beforehand finds where each element starts (for
// file:line in errors, which the parser does not keep) and refuses deep nesting.
#include "alignment/points_json.h"

#include "base/number_range.h"

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

namespace overlayd {

namespace {

struct Layout {
    std::vector<size_t> elementStarts; // byte offset of each top-level array element
    size_t tooDeepAt = std::string::npos;
};

// Walks the text outside strings; the parser checks the syntax, this only tracks depth.
Layout scanLayout(const std::string &text)
{
    Layout layout;
    int depth = 0;
    bool inString = false, expectElement = false;
    for (size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (inString) {
            if (c == '\\')
                ++i;
            else if (c == '"')
                inString = false;
            continue;
        }
        if (c == ' ' || c == '\t' || c == '\n' || c == '\r')
            continue;
        if (expectElement && c != ']')
            layout.elementStarts.push_back(i);
        expectElement = depth == 1 && c == ',';
        if (c == '"') {
            inString = true;
        } else if (c == '[' || c == '{') {
            if (++depth > kMaxPointsJsonDepth) {
                layout.tooDeepAt = i;
                return layout;
            }
            expectElement = expectElement || (depth == 1 && c == '[');
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
    return layout;
}

std::string lineOf(const std::string &text, size_t offset)
{
    return std::to_string(1 + std::count(text.begin(), text.begin() + std::min(offset, text.size()), '\n'));
}

// n finite numbers from a JSON array, or why not.
Result<std::vector<double>> numbers(const nlohmann::json &value, const char *key, size_t count)
{
    const std::string what = std::string("\"") + key + "\"";
    if (value.is_null())
        return makeError(ErrorCode::Malformed, what + " is null (that point had no " + key + ")");
    if (!value.is_array() || value.size() != count)
        return makeError(ErrorCode::Malformed, what + " must be an array of " + std::to_string(count) + " numbers");
    std::vector<double> out;
    for (const nlohmann::json &v : value) {
        if (!v.is_number() || !std::isfinite(v.get<double>()))
            return makeError(ErrorCode::Malformed, what + " must be an array of " + std::to_string(count) +
                                                       " finite numbers, got " + v.dump());
        if (const std::string why = kAnyMagnitude.refusal(v.get<double>()); !why.empty())
            return makeError(ErrorCode::Malformed, what + ": " + why);
        out.push_back(v.get<double>());
    }
    return out;
}

Result<Correspondence> correspondence(const nlohmann::json &element)
{
    if (!element.is_object() || !element.contains("world") || !element.contains("pixel"))
        return makeError(ErrorCode::Malformed, "expected {\"world\": [x, y, z], \"pixel\": [u, v]}");
    auto world = numbers(element["world"], "world", 3);
    if (!world)
        return world.error();
    auto pixel = numbers(element["pixel"], "pixel", 2);
    if (!pixel)
        return pixel.error();
    return Correspondence{{(*world)[0], (*world)[1], (*world)[2]}, {(*pixel)[0], (*pixel)[1]}};
}

} // namespace

bool looksLikeJson(const std::string &text, const std::string &name)
{
    if (name.size() >= 5 && name.compare(name.size() - 5, 5, ".json") == 0)
        return true;
    const size_t first = text.find_first_not_of(" \t\r\n");
    return first != std::string::npos && (text[first] == '[' || text[first] == '{');
}

Result<std::vector<Correspondence>> parsePointsJson(const std::string &text, const std::string &name)
{
    const Layout layout = scanLayout(text);
    if (layout.tooDeepAt != std::string::npos)
        return makeError(ErrorCode::Malformed, name + ":" + lineOf(text, layout.tooDeepAt) + ": nested deeper than " +
                                                   std::to_string(kMaxPointsJsonDepth) + " levels");
    nlohmann::json document;
    try {
        document = nlohmann::json::parse(text);
    } catch (const nlohmann::json::parse_error &e) {
        // e.byte is 1-based, the byte where the parser stopped.
        const std::string line = lineOf(text, e.byte > 0 ? e.byte - 1 : 0);
        const std::string what = e.what(); // "[json.exception.parse_error.101] parse error at ...: why"
        const size_t colon = what.find(": ");
        const std::string why = colon == std::string::npos ? what : what.substr(colon + 2);
        return makeError(ErrorCode::Malformed, name + ":" + line + ": not valid JSON (" + why + ")");
    } catch (const nlohmann::json::exception &e) {
        // A number beyond double ("number overflow parsing '1e400'"): no position given, so find the literal.
        const std::string what = e.what();
        const size_t open = what.find('\''), close = what.rfind('\'');
        const size_t at = open < close ? text.find(what.substr(open + 1, close - open - 1)) : std::string::npos;
        return makeError(ErrorCode::Malformed, name + ":" + lineOf(text, at == std::string::npos ? 0 : at) +
                                                   ": not a finite number (" + what.substr(what.find(']') + 2) + ")");
    }
    if (!document.is_array())
        return makeError(ErrorCode::Malformed,
                         name + ":1: expected an array [{\"world\": [x, y, z], \"pixel\": [u, v]}, ...]");
    std::vector<Correspondence> points;
    for (size_t i = 0; i < document.size(); ++i) {
        // Only for a message: counting lines up to every element was quadratic (10000 points: 1.3 s, 100 s under
        // ASan).
        const auto where = [&] {
            const size_t start = i < layout.elementStarts.size() ? layout.elementStarts[i] : 0;
            return name + ":" + lineOf(text, start) + ": element " + std::to_string(i) + ": ";
        };
        if (points.size() == kMaxCorrespondences)
            return makeError(ErrorCode::Malformed,
                             where() + "more than " + std::to_string(kMaxCorrespondences) + " points");
        auto point = correspondence(document[i]);
        if (!point)
            return makeError(ErrorCode::Malformed, where() + point.error().message);
        points.push_back(*point);
    }
    return points;
}

} // namespace overlayd
