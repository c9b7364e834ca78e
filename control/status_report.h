// SPDX-License-Identifier: Apache-2.0
// StatusReport: what the daemon's parts (StatusReporter) add for /state and /metrics. /state gets entries appended
// to named lists ("sinks", "inputs", "input_health") and fields set; /metrics gets samples, written family by family
// (one HELP and TYPE per name, its samples together, as the Prometheus text format wants), in the order each name
// first came.
#pragma once

#include <chrono>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "inputs/input_health.h"

namespace overlayd {

class StatusReport
{
public:
    explicit StatusReport(std::chrono::steady_clock::time_point now) : now_(now) {}

    // The time the report is made at, for ages ("age_s").
    std::chrono::steady_clock::time_point now() const { return now_; }

    // /state: an entry at the end of the list `list`, or the field `key`.
    void add(const std::string &list, nlohmann::json entry);
    void set(const std::string &key, nlohmann::json value);
    // /metrics: a sample of `name`; labels as `key="value",...` (label() makes one).
    void metric(const std::string &name, const char *type, const char *help, double value,
                const std::string &labels = {});
    // A sample of the family `family` under another name: a histogram's `family_bucket`, `_sum` and `_count`.
    void sample(const std::string &family, const char *type, const char *help, const std::string &name, double value,
                const std::string &labels = {});
    // An "inputs" entry, with `error` (why the input's last value was refused) when there is one.
    void input(nlohmann::json entry, const std::string &error);
    // One input's health, the same for every kind of input: an "input_health" entry and its two metrics.
    void health(const InputHealth &input);

    // `key="value"` with the value quoted as JSON quotes it (the text format's escapes are JSON's).
    static std::string label(const std::string &key, const std::string &value);

    // Every list added and field set, into `state` (a list nobody added to is not written).
    void writeState(nlohmann::json &state) const;
    std::string metricsText() const;

private:
    struct Family {
        std::string name, type, help;
        std::vector<std::string> samples; // "name{labels} value"
    };

    std::chrono::steady_clock::time_point now_;
    nlohmann::json state_ = nlohmann::json::object();
    std::vector<Family> families_;
    std::map<std::string, size_t, std::less<>> familyIndex_;
};

} // namespace overlayd
