// SPDX-License-Identifier: Apache-2.0
// [[sink]] kind = "record" and "push": read into DaemonConfig::stream, every bad value refused at its key with its
// line, and what starting would refuse (a missing, non-directory or shared directory; a scheme nothing can push to)
// refused by the loader, so check-config and run agree.
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include <gtest/gtest.h>

#include "config_test_util.h"
#include "stream/stream_options.h"

namespace overlayd::test {
namespace {

class EncodedSinkConfig : public ::testing::Test
{
protected:
    void SetUp() override
    {
        if (!streamBuiltIn())
            GTEST_SKIP() << "built without the encoded outputs";
        directory_ =
            std::filesystem::temp_directory_path() / ("overlayd-record-config-" + std::to_string(getpid()) + "-" +
                                                      ::testing::UnitTest::GetInstance()->current_test_info()->name());
        std::filesystem::remove_all(directory_);
        std::filesystem::create_directories(directory_);
    }
    void TearDown() override
    {
        if (!directory_.empty())
            std::filesystem::remove_all(directory_);
    }

    std::string record(const std::string &keys) const
    {
        return "[[sink]]\nkind = \"null\"\n[[sink]]\nkind = \"record\"\ndirectory = \"" + directory_.string() + "\"\n" +
               keys;
    }

    std::filesystem::path directory_;
};

TEST_F(EncodedSinkConfig, ARecordWithEveryKey)
{
    const DaemonConfig config =
        loadValid(record("segment_s = 2.5\ncontainer = \"matroska\"\nkeep_bytes = 2000000000\nkeep_days = 7\n"));
    EXPECT_EQ(config.sinks.size(), 1u); // the null sink; the recording is not a frame sink
    ASSERT_EQ(config.stream.sinks.size(), 1u);
    EXPECT_EQ(config.stream.sinks[0].key, "sink[1]");
    EXPECT_EQ(config.stream.sinks[0].kind, EncodedSinkKind::Record);
    const RecordSinkOptions &options = config.stream.sinks[0].record;
    EXPECT_EQ(options.directory, directory_.string());
    EXPECT_EQ(options.segmentSec, 2.5);
    EXPECT_EQ(options.container, RecordContainer::Matroska);
    EXPECT_EQ(options.keepBytes, 2000000000u);
    EXPECT_EQ(options.keepDays, 7.0);
}

TEST_F(EncodedSinkConfig, DefaultsAreAMinuteOfMp4KeptForever)
{
    const DaemonConfig config = loadValid(record(""));
    ASSERT_EQ(config.stream.sinks.size(), 1u);
    const RecordSinkOptions &options = config.stream.sinks[0].record;
    EXPECT_EQ(options.segmentSec, 60.0);
    EXPECT_EQ(options.container, RecordContainer::Mp4);
    EXPECT_EQ(options.keepBytes, 0u);
    EXPECT_EQ(options.keepDays, 0.0);
}

TEST_F(EncodedSinkConfig, BadValuesAreRefusedAtTheirKeys)
{
    const auto problems = loadInvalid(record("segment_s = 0.5\ncontainer = \"avi\"\nkeep_bytes = -1\n"
                                             "keep_days = 40000\npath = \"x\"\n"));
    EXPECT_TRUE(hasProblem(problems, "sink[1].segment_s", "")) << formatProblems(problems);
    EXPECT_TRUE(hasProblem(problems, "sink[1].container", "mp4")) << formatProblems(problems);
    EXPECT_TRUE(hasProblem(problems, "sink[1].keep_bytes", "")) << formatProblems(problems);
    EXPECT_TRUE(hasProblem(problems, "sink[1].keep_days", "")) << formatProblems(problems);
    EXPECT_TRUE(hasProblem(problems, "sink[1].path", "unknown")) << formatProblems(problems);
    for (const ConfigProblem &problem : problems)
        EXPECT_GT(problem.line, 0u) << problem.format();
    EXPECT_EQ(problems.size(), 5u) << formatProblems(problems);
}

TEST_F(EncodedSinkConfig, TheLimitsAreTheNamedOnes)
{
    EXPECT_TRUE(loadValid(record("segment_s = 1\nkeep_days = 36500\n")).stream.sinks.size() == 1);
    EXPECT_TRUE(loadValid(record("segment_s = 86400\nkeep_bytes = 1125899906842624\n")).stream.sinks.size() == 1);
    EXPECT_EQ(kMaxKeepBytes, 1125899906842624u);
    EXPECT_TRUE(hasProblem(loadInvalid(record("segment_s = 86401\n")), "sink[1].segment_s", ""));
    EXPECT_TRUE(hasProblem(loadInvalid(record("keep_bytes = 1125899906842625\n")), "sink[1].keep_bytes", ""));
}

TEST_F(EncodedSinkConfig, AMissingOrUnusableDirectoryIsRefusedAsRunWould)
{
    const std::string missing = (directory_ / "nope").string();
    auto problems = loadInvalid("[[sink]]\nkind = \"record\"\ndirectory = \"" + missing + "\"\n");
    ASSERT_EQ(problems.size(), 1u) << formatProblems(problems);
    EXPECT_EQ(problems[0].key, "sink[0].directory");
    EXPECT_EQ(problems[0].line, 3u);
    EXPECT_EQ(problems[0].message, "'" + missing + "' does not exist");

    const std::string file = (directory_ / "file").string();
    std::ofstream(file) << "x";
    problems = loadInvalid("[[sink]]\nkind = \"record\"\ndirectory = \"" + file + "\"\n");
    EXPECT_TRUE(hasProblem(problems, "sink[0].directory", "is not a directory")) << formatProblems(problems);

    problems = loadInvalid("[[sink]]\nkind = \"record\"\n");
    EXPECT_TRUE(hasProblem(problems, "sink[0].directory", "missing")) << formatProblems(problems);
}

TEST_F(EncodedSinkConfig, TwoRecordingsCannotShareADirectory)
{
    const auto problems = loadInvalid(record("") + "[[sink]]\nkind = \"record\"\ndirectory = \"" +
                                      (directory_ / "." / "").string() + "\"\n");
    ASSERT_EQ(problems.size(), 1u) << formatProblems(problems);
    EXPECT_EQ(problems[0].key, "sink[2].directory");
    EXPECT_NE(problems[0].message.find("recorded by sink[1] already"), std::string::npos) << problems[0].message;
}

TEST(PushConfig, EachSchemeAndItsProtocol)
{
    if (!streamBuiltIn())
        GTEST_SKIP() << "built without the encoded outputs";
    const DaemonConfig config = loadValid("[[sink]]\nkind = \"push\"\nurl = \"rtsp://127.0.0.1:8554/cam\"\n"
                                          "[[sink]]\nkind = \"push\"\nurl = \"rtmp://127.0.0.1/live/cam\"\n"
                                          "[[sink]]\nkind = \"push\"\nurl = \"srt://127.0.0.1:9000\"\n");
    ASSERT_EQ(config.stream.sinks.size(), 3u);
    EXPECT_EQ(config.stream.sinks[0].push.protocol, PushProtocol::Rtsp);
    EXPECT_EQ(config.stream.sinks[1].push.protocol, PushProtocol::Rtmp);
    EXPECT_EQ(config.stream.sinks[2].push.protocol, PushProtocol::Srt);
    EXPECT_EQ(config.stream.sinks[2].push.url, "srt://127.0.0.1:9000");
    EXPECT_EQ(config.stream.sinks[2].kind, EncodedSinkKind::Push);
    EXPECT_EQ(config.stream.sinks[2].key, "sink[2]");
    EXPECT_TRUE(config.sinks.empty());
}

TEST(PushConfig, ABadSchemeOrNoUrlIsRefused)
{
    if (!streamBuiltIn())
        GTEST_SKIP() << "built without the encoded outputs";
    auto problems = loadInvalid("[[sink]]\nkind = \"push\"\nurl = \"http://127.0.0.1/cam\"\n");
    ASSERT_EQ(problems.size(), 1u) << formatProblems(problems);
    EXPECT_EQ(problems[0].key, "sink[0].url");
    EXPECT_EQ(problems[0].line, 3u);
    EXPECT_EQ(problems[0].message, "the scheme 'http' cannot be pushed to: rtsp://, rtmp:// or srt://");
    problems = loadInvalid("[[sink]]\nkind = \"push\"\n");
    EXPECT_TRUE(hasProblem(problems, "sink[0].url", "missing")) << formatProblems(problems);
    problems = loadInvalid("[[sink]]\nkind = \"push\"\nurl = \"rtsp://" + std::string(2048, 'h') + "\"\n");
    EXPECT_TRUE(hasProblem(problems, "sink[0].url", "")) << formatProblems(problems);
}

} // namespace
} // namespace overlayd::test
