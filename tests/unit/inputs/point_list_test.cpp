// SPDX-License-Identifier: Apache-2.0
// Path files: "x y z" per line with spaces and/or commas, comments and blank lines; every malformed line is refused
// naming its line, and the point limit holds.
#include "inputs/point_list.h"

#include <gtest/gtest.h>

namespace overlayd {
namespace {

TEST(PointList, ReadsSpacesCommasCommentsAndSigns)
{
    const auto points = parsePointList("# planned route\n"
                                       "0 0 0\n"
                                       "\n"
                                       "1.5, -2.25,0.125   # a comment after a point\r\n"
                                       "\t+3e2 ,-1E-3, 4\n"
                                       "   \n",
                                       "route.txt");
    ASSERT_TRUE(points.ok()) << points.error().message;
    ASSERT_EQ(points->size(), 3u);
    EXPECT_EQ((*points)[0], glm::dvec3(0.0, 0.0, 0.0));
    EXPECT_EQ((*points)[1], glm::dvec3(1.5, -2.25, 0.125));
    EXPECT_EQ((*points)[2], glm::dvec3(300.0, -0.001, 4.0));
    EXPECT_TRUE(parsePointList("", "empty.txt")->empty());
    EXPECT_TRUE(parsePointList("# nothing yet\n", "empty.txt")->empty());
}

TEST(PointList, RefusesEachMalformedLineByNumber)
{
    const struct {
        const char *text, *words;
    } cases[] = {
        {"0 0 0\n1 2\n", "route.txt:2: 2 number(s)"},
        {"0 0 0 0\n", "route.txt:1: more than 3 numbers"},
        {"0 0 0\n\n1 abc 2\n", "route.txt:3: 'abc' is not a finite number"},
        {"1 2 nan\n", "'nan' is not a finite number"},
        {"1 2 inf\n", "'inf' is not a finite number"},
        {"1 2 1e999\n", "'1e999' is not a finite number"},
        {"1 2 3x\n", "'3x' is not a finite number"},
        {"1 2 0x10\n", "'0x10' is not a finite number"},
        {"1 2 ++3\n", "'++3' is not a finite number"},
        {"1 2 +-3\n", "'+-3' is not a finite number"},
        {"0 0 0\n1 1e7 2\n", "route.txt:2: y: out of range: must be in [-1e+06, 1e+06] (got 10000000)"},
        {"-1e300 0 0\n", "route.txt:1: x: out of range"},
    };
    for (const auto &c : cases) {
        const auto points = parsePointList(c.text, "route.txt");
        ASSERT_FALSE(points.ok()) << c.text;
        EXPECT_EQ(points.error().code, ErrorCode::Malformed);
        EXPECT_NE(points.error().message.find(c.words), std::string::npos) << points.error().message;
    }
}

TEST(PointList, HoldsAtMostTheLimit)
{
    std::string text;
    for (size_t i = 0; i < kMaxPathPoints; ++i)
        text += std::to_string(i) + " 0 0\n";
    const auto full = parsePointList(text, "long.txt");
    ASSERT_TRUE(full.ok());
    EXPECT_EQ(full->size(), kMaxPathPoints);
    EXPECT_EQ(full->back().x, double(kMaxPathPoints - 1));
    const auto over = parsePointList(text + "1 1 1\n", "long.txt");
    ASSERT_FALSE(over.ok());
    EXPECT_NE(over.error().message.find("long.txt:10001: more than 10000 points"), std::string::npos)
        << over.error().message;
}

} // namespace
} // namespace overlayd
