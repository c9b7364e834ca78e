// SPDX-License-Identifier: Apache-2.0
// The config file itself: only a regular file of at most kMaxConfigFileBytes is read (a directory, a device or a
// FIFO is refused with what it is, without blocking), and no TOML nests deeper than kMaxNestingDepth (toml++
// overflows the stack on tens of thousands of dotted key parts). Also the depth scan itself, on what real files
// hold.
#include <filesystem>
#include <fstream>
#include <string>

#include <sys/stat.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "config/nesting_depth.h"
#include "config_test_util.h"

namespace overlayd::test {
namespace {

class ConfigFileLimitsTest : public ::testing::Test
{
protected:
    void SetUp() override
    {
        dir_ =
            std::filesystem::temp_directory_path() / ("overlayd-config-limits-" + std::to_string(::getpid()) + "-" +
                                                      ::testing::UnitTest::GetInstance()->current_test_info()->name());
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }

    // The one problem loading `path` gives, formatted.
    static std::string problemOf(const std::string &path)
    {
        std::vector<ConfigProblem> problems;
        auto config = loadConfigFile(path, problems);
        EXPECT_FALSE(config.ok()) << path << " was accepted";
        EXPECT_EQ(problems.size(), 1u) << formatProblems(problems);
        return problems.empty() ? std::string() : problems.front().format();
    }

    std::string path(const std::string &name) const { return (dir_ / name).string(); }

    std::filesystem::path dir_;
};

TEST_F(ConfigFileLimitsTest, NotARegularFileSaysWhatItIs)
{
    std::filesystem::create_directories(path("conf.toml"));
    EXPECT_EQ(problemOf(path("conf.toml")),
              path("conf.toml") + ":0:0: the config file is a directory, not a regular file");
    EXPECT_EQ(problemOf("/dev/zero"), "/dev/zero:0:0: the config file is a character device, not a regular file");
    ASSERT_EQ(::mkfifo(path("fifo.toml").c_str(), 0600), 0);
    EXPECT_EQ(problemOf(path("fifo.toml")), path("fifo.toml") + ":0:0: the config file is a FIFO, not a regular file");
    EXPECT_EQ(problemOf(path("absent.toml")), path("absent.toml") + ":0:0: the config file does not exist");
}

TEST_F(ConfigFileLimitsTest, AFileOverTheLimitIsNotRead)
{
    std::ofstream(path("big.toml")) << "# " << std::string(kMaxConfigFileBytes, 'x') << "\n";
    EXPECT_EQ(problemOf(path("big.toml")), path("big.toml") + ":0:0: the config file has " +
                                               std::to_string(kMaxConfigFileBytes + 3) + " bytes; at most " +
                                               std::to_string(kMaxConfigFileBytes) + " are read");
}

// 100000 dotted key parts crash toml++ (a stack overflow) without the pre-scan. Under [daemon] the 64th part of
// the key is the 65th level.
TEST_F(ConfigFileLimitsTest, DeepDottedKeysAreRefusedWithLineAndColumn)
{
    std::string key = "a";
    for (int i = 0; i < 100000; ++i)
        key += ".b";
    std::ofstream(path("deep.toml")) << "[daemon]\nlog_level = \"info\"\n" << key << " = 1\n";
    EXPECT_EQ(problemOf(path("deep.toml")),
              path("deep.toml") + ":3:" + std::to_string(2 * 63) +
                  ": nested deeper than 64 levels (arrays, inline tables and the parts of dotted keys and table "
                  "names)");
}

TEST(NestingDepth, RealFilesPass)
{
    for (const char *name : {"demo.toml", "images.toml", "distorted_pinhole.toml", "replay.toml"}) {
        std::ifstream in(sourceDir() + "/config/examples/" + name);
        const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        ASSERT_FALSE(text.empty()) << name;
        EXPECT_FALSE(findTooDeep(text, TextSyntax::Toml, 8)) << name;
    }
    std::ifstream in(sourceDir() + "/config/examples/calibration.yaml");
    const std::string yaml((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_FALSE(findTooDeep(yaml, TextSyntax::Yaml, 3));
}

TEST(NestingDepth, CountsEachSyntaxsLevels)
{
    // Exactly the limit passes, one more is refused where it starts.
    EXPECT_FALSE(findTooDeep("a: [[1]]\n", TextSyntax::Yaml, 3));
    ASSERT_TRUE(findTooDeep("a: [[[1]]]\n", TextSyntax::Yaml, 3));
    EXPECT_EQ(findTooDeep("a: [[[1]]]\n", TextSyntax::Yaml, 3)->column, 6u);
    EXPECT_FALSE(findTooDeep("a:\n  b:\n    c: 1\n", TextSyntax::Yaml, 3));
    EXPECT_EQ(findTooDeep("a:\n  b:\n    c:\n      d: 1\n", TextSyntax::Yaml, 3)->line, 4u);
    EXPECT_EQ(findTooDeep("- - - - x\n", TextSyntax::Yaml, 3)->line, 1u);
    // Brackets in quotes, comments and inside plain words are not levels.
    EXPECT_FALSE(findTooDeep("a: '[[[[' # [[[[\nb: \"{{{{\"\nc: x[[[[\n", TextSyntax::Yaml, 2));

    EXPECT_FALSE(findTooDeep("<a><b/><b>1</b><!-- <c><c><c> --></a>", TextSyntax::Xml, 2));
    EXPECT_EQ(findTooDeep("<a>\n<b>\n<c>", TextSyntax::Xml, 2)->line, 3u);

    EXPECT_FALSE(findTooDeep("[a.b]\nc = [[1], [2]]\nd = \"[[[[.....\" # [[[[ ....\n", TextSyntax::Toml, 4));
    EXPECT_TRUE(findTooDeep("[a.b]\nc.d = 1\n", TextSyntax::Toml, 3));
    EXPECT_TRUE(findTooDeep("a = [[[[1]]]]\n", TextSyntax::Toml, 3));
    EXPECT_TRUE(findTooDeep("a = {b = {c.d.e = 1}}\n", TextSyntax::Toml, 3));
    EXPECT_FALSE(findTooDeep("a = 1.5\nb = [1.5, 2.5, 3.5, 4.5]\n", TextSyntax::Toml, 1));
}

} // namespace
} // namespace overlayd::test
