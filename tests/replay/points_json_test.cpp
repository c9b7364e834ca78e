// SPDX-License-Identifier: Apache-2.0
// solve-pose's points file as JSON, through the real binary: the same points give the same pose as the CSV form,
// `project --json`'s output goes straight back in, and bad files are refused at file:line with the element named.
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "harness.h"

namespace overlayd::test {
namespace {

std::string examples(const std::string &name)
{
    return std::string(OVERLAYD_SOURCE_DIR) + "/config/examples/" + name;
}

RunResult solve(const std::string &points, const std::string &dir)
{
    return runOverlayd("solve-pose --config '" + examples("distorted_pinhole.toml") + "' --points '" + points + "'",
                       dir);
}

// The example's six floor marks in both forms: the same output, pose and errors, to the last printed digit.
TEST(PointsJson, TheExampleGivesTheSamePoseAsTheCsv)
{
    const std::string dir = scratchDir("points-json-example");
    const RunResult csv = solve(examples("ground_marks.csv"), dir);
    const RunResult json = solve(examples("ground_marks.json"), dir);
    ASSERT_EQ(csv.exitStatus, 0) << csv.all();
    ASSERT_EQ(json.exitStatus, 0) << json.all();
    EXPECT_NE(json.out.find("rvec = ["), std::string::npos) << json.out;
    EXPECT_EQ(json.out, csv.out);
}

// `project --json` of known points through the example, then solve-pose on that very output: the example's own
// extrinsics (rvec, tvec in the config) come back.
TEST(PointsJson, ProjectJsonOutputGoesBackIntoSolvePose)
{
    const std::string dir = scratchDir("points-json-roundtrip");
    const RunResult project = runOverlayd("project --config '" + examples("distorted_pinhole.toml") +
                                              "' --json -- -1.5 1.5 0  0 1.5 0  1.5 1.5 0  -1 3 0  1 3 0  0 5 0  "
                                              "-0.5 2 0.5  0.7 4 1",
                                          dir);
    ASSERT_EQ(project.exitStatus, 0) << project.all();
    writeFile(dir + "/projected.json", project.out);
    const RunResult run = solve("projected.json", dir);
    ASSERT_EQ(run.exitStatus, 0) << run.all();
    double r[3] = {NAN, NAN, NAN}, t[3] = {NAN, NAN, NAN};
    const size_t rAt = run.out.find("\nrvec = ["), tAt = run.out.find("\ntvec = [");
    ASSERT_NE(rAt, std::string::npos) << run.out;
    ASSERT_NE(tAt, std::string::npos) << run.out;
    std::sscanf(run.out.c_str() + rAt + 9, "%lf, %lf, %lf", &r[0], &r[1], &r[2]);
    std::sscanf(run.out.c_str() + tAt + 9, "%lf, %lf, %lf", &t[0], &t[1], &t[2]);
    const double rvec[3] = {2.0943951023931957, 0.0, 0.0}, tvec[3] = {0.0, 2.1650635094610964, 1.25};
    for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(r[k], rvec[k], 1e-6) << run.out;
        EXPECT_NEAR(t[k], tvec[k], 1e-6) << run.out;
    }
}

TEST(PointsJson, RefusesBadFilesNamingTheLineAndElement)
{
    const std::string dir = scratchDir("points-json-bad");
    const std::string good = "{\"world\": [0, 1, 0], \"pixel\": [640, 500]}";
    const struct {
        const char *file, *text, *message;
    } cases[] = {
        {"missing.json", "[\n  {\"world\": [0, 1, 0], \"pixel\": [640, 500]},\n  {\"world\": [0, 2, 0]}\n]",
         "missing.json:3: element 1: expected {\"world\": [x, y, z], \"pixel\": [u, v]}"},
        {"null.json", "[{\"world\": [0, 1, 0], \"pixel\": null}]",
         "null.json:1: element 0: \"pixel\" is null (that point had no pixel)"},
        {"short.json", "[\n{\"world\": [0, 1], \"pixel\": [1, 2]}]",
         "short.json:2: element 0: \"world\" must be an array of 3 numbers"},
        {"huge.json", "[{\"world\": [0, 1, 0],\n \"pixel\": [1e400, 2]}]",
         "huge.json:2: not a finite number (number overflow parsing '1e400')"},
        {"text.json", "[{\"world\": [0, 1, 0], \"pixel\": [\"640\", 2]}]",
         "text.json:1: element 0: \"pixel\" must be an array of 2 finite numbers, got \"640\""},
        {"syntax.json", "[\n  {\"world\": [0, 1, 0], \"pixel\": [640, 500]},\n  {\"world\": [0, 2, 0],, }\n]",
         "syntax.json:3: not valid JSON"},
        {"object.json", "{\"points\": []}", "object.json:1: expected an array [{\"world\""},
        {"deep.json", "[\n[[[[1]]]]]", "deep.json:2: nested deeper than 3 levels"},
        // Detected by its first character whatever the name.
        {"marks.txt", "  [{\"world\": [0, 1, 0]}]", "marks.txt:1: element 0: expected {\"world\""},
    };
    for (const auto &c : cases) {
        writeFile(dir + "/" + c.file, c.text);
        const RunResult run = solve(c.file, dir);
        EXPECT_EQ(run.exitStatus, 1) << c.file << "\n" << run.all();
        EXPECT_NE(run.err.find(c.message), std::string::npos) << c.file << "\n" << run.all();
        EXPECT_FALSE(run.crashed);
    }
    // The limits: kMaxCorrespondences (10000) points, kMaxPointsFileBytes (1 MiB) of text.
    std::string many = "[";
    for (int i = 0; i <= 10000; ++i)
        many += (i ? ",\n" : "") + good;
    writeFile(dir + "/many.json", many + "]");
    RunResult run = solve("many.json", dir);
    EXPECT_EQ(run.exitStatus, 1);
    EXPECT_NE(run.err.find("many.json:10001: element 10000: more than 10000 points"), std::string::npos) << run.err;
    writeFile(dir + "/big.json", "[" + std::string(1 << 20, ' ') + "]");
    run = solve("big.json", dir);
    EXPECT_EQ(run.exitStatus, 1);
    EXPECT_NE(run.err.find("big.json: larger than 1048576 bytes"), std::string::npos) << run.err;
}

} // namespace
} // namespace overlayd::test
