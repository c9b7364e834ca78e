// SPDX-License-Identifier: Apache-2.0
// The one status interface: /state and /metrics write out what each part of the daemon reports of itself, so a new
// kind of input or sink shows up without an edit to the HTTP API, and a metric family's samples stay together.
#include "control/status_report.h"

#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "control/daemon_status.h"
#include "control/http_api.h"

namespace overlayd {
namespace {

using nlohmann::json;

// A kind of input the API has never heard of: its entries must reach /state and /metrics as it adds them.
struct NewKind final : StatusReporter {
    std::string name;
    double value = 0.0;
    void report(StatusReport &report) const override
    {
        report.add("inputs", {{"kind", "new"}, {"name", name}});
        report.set("new_kind", name);
        report.metric("overlayd_new_value", "gauge", "A new kind's value.", value, StatusReport::label("input", name));
        report.metric("overlayd_new_other", "gauge", "A new kind's other value.", 1.0,
                      StatusReport::label("input", name));
    }
};

struct FakeStatus final : DaemonStatus {
    DaemonConfig config_;
    StreamFormat format_{};
    std::vector<const StatusReporter *> reporters_;
    State state() const override { return State::Waiting; }
    const DaemonConfig &config() const override { return config_; }
    const StreamFormat &streamFormat() const override { return format_; }
    uint64_t framesIn() const override { return 7; }
    std::vector<const StatusReporter *> reporters() const override { return reporters_; }
};

struct StatusReportTest : ::testing::Test {
    NewKind first, second;
    FakeStatus status;
    SceneControl scene{
        [](const OverlayScene &, const Camera &, const StreamFormat &) -> Result<std::unique_ptr<OverlayRenderer>> {
            return std::unique_ptr<OverlayRenderer>();
        }};
    HttpApi api{scene, status, [] {
                    return HttpCounters{};
                }};

    void SetUp() override
    {
        first.name = "a", first.value = 2.5;
        second.name = "b", second.value = 4.0;
        status.reporters_ = {&first, &second};
        scene.load(OverlayScene{}, CameraSpec{});
    }
    HttpResponse get(const std::string &path) { return api.handle({"GET", path, {}, "", "127.0.0.1", ""}); }
};

TEST_F(StatusReportTest, StateCarriesWhatEachPartReports)
{
    const HttpResponse response = get("/state");
    ASSERT_EQ(response.status, 200u);
    const json state = json::parse(response.body);
    EXPECT_EQ(state["inputs"], json::parse(R"([{"kind": "new", "name": "a"}, {"kind": "new", "name": "b"}])"));
    EXPECT_EQ(state["new_kind"], "b");
    EXPECT_EQ(state["sinks"], json::array());     // always there, empty without sinks
    EXPECT_FALSE(state.contains("input_health")); // a list nobody added to is not written
    EXPECT_EQ(state["source"]["frames"], 7);
    EXPECT_EQ(state["source"]["state"], "waiting");
}

TEST_F(StatusReportTest, MetricFamiliesAreWrittenWholeOnce)
{
    const HttpResponse response = get("/metrics");
    ASSERT_EQ(response.status, 200u);
    // Two parts, two families each: each family once, its samples together (the Prometheus text format).
    const std::string expected = "# HELP overlayd_new_value A new kind's value.\n"
                                 "# TYPE overlayd_new_value gauge\n"
                                 "overlayd_new_value{input=\"a\"} 2.5\n"
                                 "overlayd_new_value{input=\"b\"} 4.0\n"
                                 "# HELP overlayd_new_other A new kind's other value.\n"
                                 "# TYPE overlayd_new_other gauge\n"
                                 "overlayd_new_other{input=\"a\"} 1.0\n"
                                 "overlayd_new_other{input=\"b\"} 1.0\n";
    EXPECT_NE(response.body.find(expected), std::string::npos) << response.body;
    EXPECT_NE(response.body.find("overlayd_source_frames_total 7.0\n"), std::string::npos) << response.body;
}

TEST(StatusReport, InputHealthIsOneEntryAndTwoSamples)
{
    const auto now = std::chrono::steady_clock::now();
    InputHealth health("text", "speed", "/run/speed.txt", InputHealth::State::Waiting, now);
    health.errors = 3;
    StatusReport report(now);
    report.health(health);
    json state = json::object();
    report.writeState(state);
    ASSERT_EQ(state["input_health"].size(), 1u);
    EXPECT_EQ(state["input_health"][0]["state"], "waiting");
    EXPECT_EQ(state["input_health"][0]["errors"], 3);
    EXPECT_EQ(state["input_health"][0]["last_error"], nullptr);
    const std::string text = report.metricsText();
    EXPECT_NE(text.find("overlayd_input_following{kind=\"text\",input=\"speed\"} 0.0\n"), std::string::npos) << text;
    EXPECT_NE(text.find("overlayd_input_errors_total{kind=\"text\",input=\"speed\"} 3.0\n"), std::string::npos) << text;
}

} // namespace
} // namespace overlayd
