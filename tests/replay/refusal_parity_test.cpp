// SPDX-License-Identifier: Apache-2.0
// check-config promises what run does: every config of tests/data/config/refusals/ is refused by check-config,
// render and run alike, through the real binary, with the same "file:line:column: key: reason" line and exit
// status 2; every config of tests/data/config/accepted/ is accepted by all three. A row is a file: its first line
// says where it must be refused ("# refused at: LINE:COLUMN: KEY: REASON WORDS"), or nothing for an accepted one.
// A row about an optional part (libmicrohttpd, libcamera, libgpiod) says so on its second line ("# needs: http",
// "libcamera" or "gpiod") and is skipped in a build without it: there the whole section is refused instead.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "harness.h"

namespace overlayd::test {
namespace {

namespace fs = std::filesystem;

struct Row {
    std::string path;    // the config, absolute
    std::string refusal; // "LINE:COLUMN: KEY: WORDS" from its first line; empty: it must be accepted
    std::string needs;   // the optional part it needs ("http", "libcamera", "gpiod", "stream"), from its second line
};

// Whether this build has the optional part a row needs (OVERLAYD_FEATURES: " http libcamera gpiod ", from CMake).
bool built(const Row &row)
{
    return row.needs.empty() || std::string(OVERLAYD_FEATURES).find(" " + row.needs + " ") != std::string::npos;
}

void PrintTo(const Row &row, std::ostream *out)
{
    *out << fs::path(row.path).filename().string();
}

std::vector<Row> rows(const std::string &folder)
{
    std::vector<Row> out;
    for (const auto &entry : fs::directory_iterator(std::string(OVERLAYD_SOURCE_DIR) + "/tests/data/config/" + folder))
        if (entry.path().extension() == ".toml") {
            std::ifstream in(entry.path());
            std::string first, second;
            std::getline(in, first);
            std::getline(in, second);
            const std::string marker = "# refused at: ", needs = "# needs: ";
            out.push_back(Row{entry.path().string(), first.rfind(marker, 0) == 0 ? first.substr(marker.size()) : "",
                              second.rfind(needs, 0) == 0 ? second.substr(needs.size()) : ""});
        }
    std::sort(out.begin(), out.end(), [](const Row &a, const Row &b) { return a.path < b.path; });
    return out;
}

// The whole line of `text` that holds `part`, or empty.
std::string lineWith(const std::string &text, const std::string &part)
{
    const size_t at = text.find(part);
    if (at == std::string::npos)
        return {};
    const size_t begin = text.rfind('\n', at) == std::string::npos ? 0 : text.rfind('\n', at) + 1;
    const size_t end = std::min(text.find('\n', at), text.size());
    return text.substr(begin, end - begin);
}

// The problem line as check-config prints it ("PATH:LINE:COLUMN: KEY: reason"), from its position on.
std::string problemFrom(const std::string &line, const std::string &path)
{
    const size_t at = line.find(path);
    return at == std::string::npos ? line : line.substr(at);
}

struct Verdicts {
    RunResult check, render, run;
};

Verdicts runAll(const Row &row)
{
    const std::string dir = scratchDir("parity-" + fs::path(row.path).stem().string());
    return Verdicts{runOverlayd("check-config '" + row.path + "'", dir),
                    runOverlayd("render --config '" + row.path + "' --frames 1 --output out.y4m", dir),
                    runOverlayd("run --config '" + row.path + "' --frames 1", dir)};
}

class Refusals : public ::testing::TestWithParam<Row>
{};

TEST_P(Refusals, CheckConfigRenderAndRunRefuseWithTheSameLocatedProblem)
{
    const Row row = GetParam();
    ASSERT_FALSE(row.refusal.empty()) << row.path << ": the first line must be '# refused at: LINE:COLUMN: KEY: ...'";
    if (!built(row))
        GTEST_SKIP() << "this overlayd was built without " << row.needs;
    const Verdicts v = runAll(row);
    const std::string expected = fs::path(row.path).filename().string() + ":" + row.refusal;
    const std::string line = lineWith(v.check.out, expected);
    ASSERT_FALSE(line.empty()) << "check-config does not say '" << expected << "':\n" << v.check.all();
    const std::string problem = problemFrom(line, row.path);
    for (const RunResult *result : {&v.check, &v.render, &v.run}) {
        EXPECT_FALSE(result->crashed) << result->all();
        EXPECT_EQ(result->exitStatus, 2) << result->all();
        EXPECT_NE(result->all().find(problem), std::string::npos)
            << "not the same problem as check-config's '" << problem << "':\n"
            << result->all();
    }
}

INSTANTIATE_TEST_SUITE_P(Corpus, Refusals, ::testing::ValuesIn(rows("refusals")),
                         [](const auto &param) { return fs::path(param.param.path).stem().string(); });

// The sweep: what check-config accepts, run and render accept too (exit 0 after one frame).
class Accepted : public ::testing::TestWithParam<Row>
{};

TEST_P(Accepted, CheckConfigRenderAndRunAllAccept)
{
    if (!built(GetParam()))
        GTEST_SKIP() << "this overlayd was built without " << GetParam().needs;
    const Verdicts v = runAll(GetParam());
    for (const RunResult *result : {&v.check, &v.render, &v.run}) {
        EXPECT_FALSE(result->crashed) << result->all();
        EXPECT_EQ(result->exitStatus, 0) << result->all();
    }
}

INSTANTIATE_TEST_SUITE_P(Corpus, Accepted, ::testing::ValuesIn(rows("accepted")),
                         [](const auto &param) { return fs::path(param.param.path).stem().string(); });

// Every example under config/examples/ passes check-config and renders a frame through the real binary, from
// another folder (its input paths resolve against its own folder); only a camera device's example cannot render
// here. replay.toml replays the recording shipped beside it.
TEST(Examples, EveryExamplePassesCheckConfigAndRenders)
{
    const std::string dir = scratchDir("examples");
    int rendered = 0;
    for (const auto &entry : fs::directory_iterator(std::string(OVERLAYD_SOURCE_DIR) + "/config/examples")) {
        if (entry.path().extension() != ".toml")
            continue;
        const std::string path = entry.path().string();
        SCOPED_TRACE(path);
        const RunResult check = runOverlayd("check-config '" + path + "'", dir);
        EXPECT_EQ(check.exitStatus, 0) << check.all();
        if (entry.path().filename() == "v4l2_camera.toml")
            continue;
        const RunResult render = runOverlayd("render --config '" + path + "' --frames 1 --output out.y4m", dir);
        EXPECT_EQ(render.exitStatus, 0) << render.all();
        ++rendered;
    }
    EXPECT_GE(rendered, 7);
}

// "did you mean" and the problem list cost bounded work: an unknown key of 100 KB and 10000 unknown keys each get
// an answer from check-config and run (no timing: that they return), in a bounded number of bounded lines.
TEST(BoundedSuggestions, HugeAndManyUnknownKeysGetAShortAnswer)
{
    const std::string dir = scratchDir("bounded-suggestions");
    std::string many = "[daemon]\n";
    for (int i = 0; i < 10000; ++i)
        many += "unknown_" + std::to_string(i) + " = 1\n";
    writeFile(dir + "/huge_key.toml", "[daemon]\n" + std::string(100000, 'k') + " = 1\n");
    writeFile(dir + "/many_keys.toml", many);
    for (const std::string &name : std::vector<std::string>{"huge_key.toml", "many_keys.toml"})
        for (const std::string &args : {"check-config " + name, "run --config " + name + " --frames 1"}) {
            SCOPED_TRACE(args);
            const RunResult result = runOverlayd(args, dir);
            EXPECT_FALSE(result.crashed);
            EXPECT_EQ(result.exitStatus, 2) << result.all().substr(0, 2000);
            EXPECT_LT(result.all().size(), 40000u) << result.all().substr(0, 2000); // 100 lines of < 300 bytes
            EXPECT_NE(result.all().find(name + ":2:1: daemon."), std::string::npos) << result.all().substr(0, 2000);
        }
}

} // namespace
} // namespace overlayd::test
