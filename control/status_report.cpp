// SPDX-License-Identifier: Apache-2.0
#include "control/status_report.h"

#include <ctime>

#include "base/number_text.h"
#include "config/json_body.h"

namespace overlayd {

namespace {

using nlohmann::json;

// A wall-clock time as ISO 8601 UTC with milliseconds: "2026-11-27T11:43:25.123Z".
std::string utcTime(std::chrono::system_clock::time_point time)
{
    const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(time.time_since_epoch()).count();
    const std::time_t seconds = std::time_t(ms / 1000);
    std::tm utc{};
    ::gmtime_r(&seconds, &utc);
    char text[32]; // "YYYY-MM-DDTHH:MM:SS" is 19 characters for any year strftime can print in 4 digits
    const size_t length = std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%S", &utc);
    return std::string(text, length) + formatted(".%03dZ", int(ms % 1000));
}

} // namespace

void StatusReport::add(const std::string &list, json entry)
{
    json &entries = state_[list];
    if (entries.is_null())
        entries = json::array();
    entries.push_back(std::move(entry));
}

void StatusReport::set(const std::string &key, json value)
{
    state_[key] = std::move(value);
}

void StatusReport::metric(const std::string &name, const char *type, const char *help, double value,
                          const std::string &labels)
{
    sample(name, type, help, name, value, labels);
}

void StatusReport::sample(const std::string &family, const char *type, const char *help, const std::string &name,
                          double value, const std::string &labels)
{
    auto found = familyIndex_.find(family);
    if (found == familyIndex_.end()) {
        found = familyIndex_.emplace(family, families_.size()).first;
        families_.push_back({family, type, help, {}});
    }
    families_[found->second].samples.push_back(name + (labels.empty() ? "" : "{" + labels + "}") + " " +
                                               writeJson(json(value)));
}

void StatusReport::input(json entry, const std::string &error)
{
    if (!error.empty())
        entry["error"] = error;
    add("inputs", std::move(entry));
}

void StatusReport::health(const InputHealth &input)
{
    add("input_health",
        {{"kind", input.kind},
         {"name", input.name},
         {"source", input.source},
         {"state", inputStateName(input.state)},
         {"state_age_s", std::chrono::duration<double>(now_ - input.since).count()},
         {"errors", input.errors},
         {"last_error", input.lastError.empty() ? json(nullptr) : json(input.lastError)},
         {"last_error_at", input.lastError.empty() ? json(nullptr) : json(utcTime(input.lastErrorAt))}});
    const std::string labels = label("kind", input.kind) + "," + label("input", input.name);
    metric("overlayd_input_following", "gauge", "1 while an input follows its file or interface, 0 while it waits.",
           input.state == InputHealth::State::Following ? 1.0 : 0.0, labels);
    metric("overlayd_input_errors_total", "counter",
           "Errors an input met (its folder or interface gone, a version refused).", double(input.errors), labels);
}

std::string StatusReport::label(const std::string &key, const std::string &value)
{
    return key + "=" + writeJson(json(value));
}

void StatusReport::writeState(json &state) const
{
    for (const auto &[key, value] : state_.items())
        state[key] = value;
}

std::string StatusReport::metricsText() const
{
    std::string text;
    for (const Family &family : families_) {
        text += "# HELP " + family.name + " " + family.help + "\n# TYPE " + family.name + " " + family.type + "\n";
        for (const std::string &sample : family.samples)
            text += sample + "\n";
    }
    return text;
}

} // namespace overlayd
