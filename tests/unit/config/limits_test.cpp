// SPDX-License-Identifier: Apache-2.0
// The limits of docs/config.md "Limits": every number has a range (the message gives it, for a large finite value as
// for inf), counts and lengths are refused at the first entry over, the renderer's own rules and the sinks' are
// refused at their key by the loader (so that check-config refuses what run would), and "did you mean" costs
// bounded work. Each expectation is the whole "file:line:column: key: reason" line.
#include <string>

#include <gtest/gtest.h>

#include "config/limits.h"
#include "config/problems.h"
#include "config_test_util.h"

namespace overlayd::test {
namespace {

// The problems' lines, one per line.
std::string problemsOf(const std::string &text)
{
    return formatProblems(loadInvalid(text));
}

#define EXPECT_REFUSED(text, line) EXPECT_NE(problemsOf(text).find(line), std::string::npos) << problemsOf(text)

TEST(Limits, ALargeFiniteNumberIsOutOfItsRangeNotInfinite)
{
    EXPECT_REFUSED("[[frame]]\nname = \"a\"\ntranslation = [1e300, 0, 0]\n",
                   "test.toml:3:16: frame[0].translation[0]: out of range: must be in [-1e+06, 1e+06] (got 1e+300)\n");
    EXPECT_REFUSED("[[frame]]\nname = \"a\"\ntranslation = [0, inf, 0]\n",
                   "test.toml:3:19: frame[0].translation[1]: out of range: must be in [-1e+06, 1e+06] (got inf)\n");
    EXPECT_REFUSED("[camera]\nfar = 1e300\n",
                   "test.toml:2:7: camera.far: out of range: must be in (0, 1e+09] (got 1e+300)\n");
    EXPECT_REFUSED("[source]\nfps = 0\n", "test.toml:2:7: source.fps: out of range: must be in (0, 1000] (got 0)\n");
}

TEST(Limits, StatsIntervalIsOffOrAtLeastATenthOfASecond)
{
    EXPECT_REFUSED("[daemon]\nstats_interval = 1e-9\n",
                   "test.toml:2:18: daemon.stats_interval: out of range: must be 0 (off) or in [0.1, 86400] s\n");
    EXPECT_EQ(loadValid("[daemon]\nstats_interval = 0\n").daemon.statsIntervalSec, 0.0);
    EXPECT_EQ(loadValid("[daemon]\nstats_interval = 0.1\n").daemon.statsIntervalSec, 0.1);
}

TEST(Limits, ViewportEntriesStayFarInsideInt)
{
    EXPECT_REFUSED("[viewport]\nwindow = [2147483000, 0, 1000, 48]\n",
                   "test.toml:2:11: viewport.window[0]: out of range: must be in [-65536, 65536] (got 2147483000)\n");
    EXPECT_REFUSED(
        "[viewport]\nscissor = [0, 0, 10, 0.5]\n",
        "test.toml:2:11: viewport.scissor: expected [x, y, width, height] in pixels with a size of at least 1\n");
}

TEST(Limits, CountsAreRefusedAtTheFirstEntryOver)
{
    std::string sinks;
    for (size_t i = 0; i <= kMaxSinks; ++i)
        sinks += "[[sink]]\nkind = \"null\"\n"; // sink[i] starts on line 2i + 1
    EXPECT_REFUSED(sinks, "test.toml:33:1: sink[16]: too many [[sink]] tables: at most 16 (got 17)\n");

    std::string points = "[[annotation]]\ntype = \"polyline\"\npoints = [";
    for (size_t i = 0; i <= kMaxWorldPoints; ++i)
        points += "[0,0,0],"; // 8 characters each, from column 11
    EXPECT_REFUSED(points + "]\n", "test.toml:3:80011: annotation[0].points[10000]: too many points: at most 10000 "
                                   "(got 10001)\n");

    EXPECT_REFUSED("[[annotation]]\ntype = \"axes\"\nstyle = { dash = [1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1] }\n",
                   "test.toml:3:51: annotation[0].style.dash[16]: too many numbers: at most 16 (got 17)\n");

    std::string annotations;
    for (size_t i = 0; i <= kMaxAnnotations; ++i)
        annotations += "[[annotation]]\ntype = \"axes\"\n";
    EXPECT_REFUSED(annotations, "test.toml:2049:1: annotation[1024]: too many [[annotation]] tables: at most 1024 "
                                "(got 1025)\n");
}

TEST(Limits, TextAndNamesHaveAMaximumLength)
{
    EXPECT_REFUSED("[[annotation]]\ntype = \"text\"\ntext = \"" + std::string(kMaxAnnotationTextBytes + 1, 'x') +
                       "\"\n",
                   "test.toml:3:8: annotation[0].text: too long: at most 1024 bytes (got 1025)\n");
    EXPECT_REFUSED("[[frame]]\nname = \"" + std::string(kMaxNameBytes + 1, 'f') + "\"\n",
                   "test.toml:2:8: frame[0].name: too long: at most 256 bytes (got 257)\n");
}

// The renderer's rules (overlay/shapes/scene_checks.cpp) reach check-config through the loader, at the key.
TEST(Limits, TheRenderersRulesAreRefusedAtTheirKey)
{
    EXPECT_REFUSED("[[annotation]]\ntype = \"text\"\ntext = \"speed {nope}\"\n",
                   "test.toml:3:8: annotation[0].text: unknown token {nope} in text");
    EXPECT_REFUSED("[[annotation]]\ntype = \"rect\"\nsize = [0, 10]\n",
                   "test.toml:3:8: annotation[0].size: rect position must be finite and its size > 0\n");
    EXPECT_REFUSED("[[annotation]]\ntype = \"axes\"\nstyle = { dash = [1e-9, 1e-9] }\n",
                   "test.toml:3:18: annotation[0].style.dash: a dash pattern must add up to at least 1 px");
    EXPECT_REFUSED("[[annotation]]\ntype = \"grid\"\nspacing = 1\nextent = 5000\n",
                   "test.toml:3:11: annotation[0].spacing: grid has more than 4000 lines");
}

TEST(Limits, AFrameChainMayNotComposeBeyondItsLimit)
{
    EXPECT_REFUSED("[[frame]]\nname = \"a\"\nscale = 1e6\n[[frame]]\nname = \"b\"\nparent = \"a\"\nscale = 1e6\n",
                   "test.toml:4:1: frame[1]: its transform from the world (the product of its parents' scales and "
                   "translations and its own) reaches 1e+12; at most 1e+09 is allowed\n");
    loadValid("[[frame]]\nname = \"a\"\nscale = 1e3\n[[frame]]\nname = \"b\"\nparent = \"a\"\nscale = 1e3\n");
}

TEST(Limits, SinksAreRefusedAtTheirPathAsBuildingThemWould)
{
    EXPECT_REFUSED("[[sink]]\nkind = \"y4m\"\npath = \"/\"\n",
                   "test.toml:3:8: sink[0].path: '/' is a directory: a file sink writes a file, a FIFO or a character "
                   "device\n");
    EXPECT_REFUSED("[[sink]]\nkind = \"snapshot\"\npath = \"shot.bmp\"\n",
                   "test.toml:3:8: sink[0].path: a snapshot path must end in .png, .jpg or .jpeg\n");
    EXPECT_REFUSED("[[sink]]\nkind = \"raw\"\npath = \"/dev/null/x.raw\"\n",
                   "test.toml:3:8: sink[0].path: '/dev/null/x.raw' is in '/dev/null', which is not a folder: a file "
                   "sink writes a file, a FIFO or a character device\n");
    EXPECT_REFUSED("[[sink]]\nkind = \"v4l2\"\npath = \"/dev/video8\"\nzero_copy = \"on\"\n"
                   "[[sink]]\nkind = \"v4l2\"\npath = \"/dev/video9\"\nzero_copy = \"on\"\n",
                   "test.toml:8:13: sink[1].zero_copy: only one sink can hold the camera's buffers, and "
                   "sink[0].zero_copy = \"on\" already does\n");
}

// No timing: the point is that these return, and that what they say stays short.
TEST(Limits, SuggestionsAndProblemListsAreBounded)
{
    const std::string huge(100000, 'k');
    const auto one = loadInvalid("[daemon]\n" + huge + " = 1\n");
    ASSERT_EQ(one.size(), 1u);
    EXPECT_LT(one[0].format().size(), 300u) << one[0].format().substr(0, 300);
    EXPECT_NE(one[0].message.find("unknown key 'kkkk"), std::string::npos);
    EXPECT_NE(one[0].message.find("(100000 bytes)"), std::string::npos);

    std::string many = "[daemon]\n";
    for (int i = 0; i < 10000; ++i)
        many += "unknown_" + std::to_string(i) + std::string(200, 'z') + " = 1\n";
    const auto listed = loadInvalid(many);
    ASSERT_EQ(listed.size(), kMaxListedProblems + 1);
    EXPECT_EQ(listed.back().message, "9900 more problem(s) not listed");
    for (const ConfigProblem &problem : listed)
        EXPECT_LT(problem.format().size(), 300u);

    EXPECT_EQ(closestMatch(std::string(1000, 'a'), {std::string(1000, 'a')}), "");
    EXPECT_EQ(closestMatch("widht", {"height", "width"}), "width");
}

} // namespace
} // namespace overlayd::test
