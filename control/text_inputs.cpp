// SPDX-License-Identifier: Apache-2.0
#include "control/text_inputs.h"

#include "control/status_report.h"

namespace overlayd {

Status TextInputs::configure(const std::vector<TextInputOptions> &options)
{
    std::vector<TextFileWatch> watches;
    std::vector<Reading> readings;
    std::vector<std::string> names;
    for (const TextInputOptions &input : options) {
        auto watch = TextFileWatch::open(input.file, input.maxBytes);
        if (!watch)
            return makeError(watch.error().code, "input.text '" + input.slot + "': " + watch.error().message);
        watches.push_back(std::move(*watch));
        names.push_back(input.slot);
        readings.push_back({input.slot, input.file, {}, {}, {}});
    }
    files_.replace(std::move(watches), names);
    readings_ = std::move(readings);
    showAll();
    return Ok{};
}

void TextInputs::showAll()
{
    for (size_t i = 0; i < files_.size(); ++i)
        show(i);
}

void TextInputs::show(size_t input)
{
    Reading &reading = readings_[input];
    std::string text = files_[input].read();
    if (text == reading.text && reading.changed != std::chrono::steady_clock::time_point{} && reading.error.empty())
        return; // a write that changed nothing the slot shows (after a refusal, the shown text again clears it)
    if (auto applied = scene_.apply(TextChange{reading.slot, text}); !applied) {
        reading.error = applied.error().message;
        logger_.warning(
            cat("input.text '", reading.slot, "' (", reading.file, "): ", reading.error, " (the text shown stays)"));
        files_.fail(input, reading.error);
        return;
    }
    reading.error.clear();
    reading.text = std::move(text);
    reading.changed = std::chrono::steady_clock::now();
    logger_.debug(cat("input.text '", reading.slot, "': \"", reading.text, "\""));
}

void TextInputs::report(StatusReport &report) const
{
    for (const Reading &reading : readings_) {
        nlohmann::json entry = {{"kind", "text"},
                                {"slot", reading.slot},
                                {"file", reading.file},
                                {"value", reading.text},
                                {"age_s", std::chrono::duration<double>(report.now() - reading.changed).count()}};
        report.input(std::move(entry), reading.error);
    }
    files_.report(report);
}

} // namespace overlayd
