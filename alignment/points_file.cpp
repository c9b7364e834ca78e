// SPDX-License-Identifier: Apache-2.0
// readPointsFile: five finite numbers (each within kAnyMagnitude) per non-empty line after an optional header row,
// every problem at file:line.
#include "alignment/points_file.h"
#include "alignment/points_json.h"
#include "base/number_range.h"
#include "base/utf8.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>
#include <utility>

namespace overlayd {

namespace {

bool isSeparator(char c)
{
    return c == ' ' || c == '\t' || c == ',' || c == '\r';
}

// The fields of one line, split at commas and/or blanks.
std::vector<std::string_view> fieldsOf(std::string_view line)
{
    std::vector<std::string_view> fields;
    for (size_t at = 0; at < line.size();) {
        if (isSeparator(line[at])) {
            ++at;
            continue;
        }
        size_t stop = at;
        while (stop < line.size() && !isSeparator(line[stop]))
            ++stop;
        fields.push_back(line.substr(at, stop - at));
        at = stop;
    }
    return fields;
}

// One number, the whole field (std::from_chars: one rounding to double, no locale; a leading '+' as other
// programs write it).
std::optional<double> numberOf(std::string_view field)
{
    const char *first = field.data() + (field.size() > 1 && field[0] == '+' && field[1] != '-' ? 1 : 0);
    double value = 0.0;
    const auto [end, error] = std::from_chars(first, field.data() + field.size(), value);
    if (error != std::errc() || end != field.data() + field.size())
        return std::nullopt;
    return value;
}

// A column name of a spreadsheet's header row ("x", "u_px", "\"Mark\""): a word with a letter that is no number.
bool isName(std::string_view field)
{
    return !numberOf(field) && std::any_of(field.begin(), field.end(),
                                           [](char c) { return std::isalpha(static_cast<unsigned char>(c)) != 0; });
}

} // namespace

Result<std::vector<PointRow>> parsePointRows(const std::string &text, const std::string &name, bool needPixels)
{
    std::vector<PointRow> rows;
    std::istringstream in(text);
    std::string line;
    bool first = true;
    for (unsigned number = 1; std::getline(in, line); ++number) {
        const std::vector<std::string_view> fields = fieldsOf(std::string_view(line).substr(0, line.find('#')));
        if (fields.empty())
            continue;
        const std::string where = name + ":" + std::to_string(number) + ": ";
        // The first line may name the columns (x,y,z,u,v as a spreadsheet exports them); only the first.
        if (std::exchange(first, false) && std::all_of(fields.begin(), fields.end(), isName))
            continue;
        std::vector<double> v;
        for (std::string_view field : fields) {
            const std::optional<double> value = numberOf(field);
            const std::string why =
                !value || !std::isfinite(*value) ? "is not a finite number" : kAnyMagnitude.refusal(*value);
            if (!why.empty())
                return makeError(ErrorCode::Malformed, where + "'" + quotable(field, kQuotedFieldBytes) + "' " + why);
            v.push_back(*value);
        }
        if (v.size() != 5 && (needPixels || v.size() != 3))
            return makeError(ErrorCode::Malformed,
                             where + (needPixels ? "expected x y z u v, got " : "expected x y z or x y z u v, got ") +
                                 std::to_string(v.size()) + " numbers");
        if (rows.size() == kMaxCorrespondences)
            return makeError(ErrorCode::Malformed,
                             where + "more than " + std::to_string(kMaxCorrespondences) + " points");
        rows.push_back({{v[0], v[1], v[2]}, v.size() == 5 ? std::optional(glm::dvec2(v[3], v[4])) : std::nullopt});
    }
    return rows;
}

Result<std::vector<Correspondence>> parsePoints(const std::string &text, const std::string &name)
{
    if (looksLikeJson(text, name))
        return parsePointsJson(text, name);
    auto rows = parsePointRows(text, name, true);
    if (!rows)
        return rows.error();
    std::vector<Correspondence> points;
    points.reserve(rows->size());
    for (const PointRow &row : *rows)
        points.push_back({row.world, *row.pixel});
    return points;
}

Result<std::vector<glm::dvec3>> parseWorldPoints(const std::string &text, const std::string &name)
{
    std::vector<glm::dvec3> world;
    if (looksLikeJson(text, name)) {
        auto points = parsePointsJson(text, name);
        if (!points)
            return points.error();
        for (const Correspondence &c : *points)
            world.push_back(c.world);
        return world;
    }
    auto rows = parsePointRows(text, name, false);
    if (!rows)
        return rows.error();
    for (const PointRow &row : *rows)
        world.push_back(row.world);
    return world;
}

Result<std::vector<Correspondence>> readPointsFile(const std::string &path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in)
        return makeError(ErrorCode::NotFound, path + ": cannot open the points file");
    std::string text(kMaxPointsFileBytes + 1, '\0');
    in.read(text.data(), std::streamsize(text.size()));
    text.resize(size_t(in.gcount()));
    if (text.size() > kMaxPointsFileBytes)
        return makeError(ErrorCode::Malformed,
                         path + ": larger than " + std::to_string(kMaxPointsFileBytes) + " bytes");
    return parsePoints(text, path);
}

} // namespace overlayd
