// readPointsFile: five finite numbers (each within kAnyMagnitude) per non-empty line, every problem at file:line.
#include "alignment/points_file.h"
#include "alignment/points_json.h"
#include "base/number_range.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

namespace overlayd::alignment {

namespace {

// The numbers of one line, or why not (std::from_chars: one rounding to double, no locale).
Result<std::vector<double>> numbersOf(const std::string &line)
{
    std::vector<double> numbers;
    const char *p = line.data(), *end = line.data() + line.size();
    while (p < end) {
        if (*p == ' ' || *p == '\t' || *p == ',' || *p == '\r') {
            ++p;
            continue;
        }
        double value = 0.0;
        const auto [next, error] = std::from_chars(p, end, value);
        const std::string why =
            error != std::errc() || !std::isfinite(value) ? "is not a finite number" : kAnyMagnitude.refusal(value);
        if (!why.empty()) {
            const std::string word(p, std::find_if(p, end, [](char c) { return c == ' ' || c == ',' || c == '\t'; }));
            return makeError(ErrorCode::Malformed, "'" + word + "' " + why);
        }
        numbers.push_back(value);
        p = next;
    }
    return numbers;
}

} // namespace

Result<std::vector<Correspondence>> parsePoints(const std::string &text, const std::string &name)
{
    if (looksLikeJson(text, name))
        return parsePointsJson(text, name);
    std::vector<Correspondence> points;
    std::istringstream in(text);
    std::string line;
    for (unsigned number = 1; std::getline(in, line); ++number) {
        line = line.substr(0, line.find('#'));
        auto numbers = numbersOf(line);
        const std::string where = name + ":" + std::to_string(number) + ": ";
        if (!numbers)
            return makeError(ErrorCode::Malformed, where + numbers.error().message);
        if (numbers->empty())
            continue;
        if (numbers->size() != 5)
            return makeError(ErrorCode::Malformed,
                             where + "expected x y z u v, got " + std::to_string(numbers->size()) + " numbers");
        if (points.size() == kMaxCorrespondences)
            return makeError(ErrorCode::Malformed,
                             where + "more than " + std::to_string(kMaxCorrespondences) + " points");
        const std::vector<double> &v = *numbers;
        points.push_back({{v[0], v[1], v[2]}, {v[3], v[4]}});
    }
    return points;
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

} // namespace overlayd::alignment
