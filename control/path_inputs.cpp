// SPDX-License-Identifier: Apache-2.0
#include "control/path_inputs.h"

#include "control/status_report.h"
#include "inputs/point_list.h"

namespace overlayd {

Status PathInputs::configure(const std::vector<PathInputOptions> &options)
{
    std::vector<TextFileWatch> watches;
    std::vector<Reading> readings;
    std::vector<std::string> names;
    for (const PathInputOptions &input : options) {
        auto watch = TextFileWatch::open(input.file, kMaxPathFileBytes, TextFileWatch::Reread::WhenComplete);
        if (!watch)
            return makeError(watch.error().code, "input.path '" + input.annotation + "': " + watch.error().message);
        watches.push_back(std::move(*watch));
        names.push_back(input.annotation);
        readings.push_back({input.annotation, input.file, 0, {}, {}});
    }
    files_.replace(std::move(watches), names);
    readings_ = std::move(readings);
    return Ok{};
}

void PathInputs::showAll()
{
    for (size_t i = 0; i < files_.size(); ++i)
        show(i);
}

void PathInputs::show(size_t input)
{
    Reading &reading = readings_[input];
    const std::string content = files_[input].readPrefix(kMaxPathFileBytes);
    Result<std::vector<glm::dvec3>> points =
        content.size() > kMaxPathFileBytes
            ? Result<std::vector<glm::dvec3>>(makeError(
                  ErrorCode::Malformed, reading.file + ": more than " + std::to_string(kMaxPathFileBytes) + " bytes"))
            : parsePointList(content, reading.file);
    Status applied = points ? scene_.apply(PointsChange{reading.annotation, *points}) : Status(points.error());
    if (!applied) {
        reading.error = applied.error().message;
        files_.fail(input, reading.error);
        logger_.warning(cat("input.path '", reading.annotation, "': ", reading.error, " (the points shown stay)"));
        return;
    }
    reading.error.clear();
    reading.points = points->size();
    reading.changed = std::chrono::steady_clock::now();
    logger_.debug(cat("input.path '", reading.annotation, "': ", reading.points, " points"));
}

void PathInputs::report(StatusReport &report) const
{
    for (const Reading &reading : readings_) {
        nlohmann::json entry = {{"kind", "path"},
                                {"annotation", reading.annotation},
                                {"file", reading.file},
                                {"points", reading.points},
                                {"age_s", std::chrono::duration<double>(report.now() - reading.changed).count()}};
        report.input(std::move(entry), reading.error);
    }
    files_.report(report);
}

} // namespace overlayd
