// SPDX-License-Identifier: Apache-2.0
// An RTSP sink's `auth` and `tls`: what they resolve to from [http] (its users and tokens, its certificate), and the
// one they refuse (a credential asked where [http] has none).
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include <gtest/gtest.h>

#include "config_test_util.h"
#include "stream/stream_options.h"

namespace overlayd::test {
namespace {

const std::string kBase = kMinimalConfig;

class RtspAccessConfig : public ::testing::Test
{
protected:
    void SetUp() override
    {
        if (!streamBuiltIn())
            GTEST_SKIP() << "built without the encoded outputs";
        folder_ =
            std::filesystem::temp_directory_path() / ("overlayd-rtsp-access-" + std::to_string(getpid()) + "-" +
                                                      ::testing::UnitTest::GetInstance()->current_test_info()->name());
        std::filesystem::create_directories(folder_);
        std::ofstream(folder_ / "users") << "watcher:viewer:see:it\nboss:control:c0ntrol\n";
        std::ofstream(folder_ / "viewer.token") << "viewer-token\n";
    }
    void TearDown() override
    {
        if (!folder_.empty())
            std::filesystem::remove_all(folder_);
    }

    // [http] with the users and the viewer token, its `viewer` as given, and one RTSP sink with `sinkKeys`.
    std::string config(const std::string &viewer, const std::string &sinkKeys) const
    {
        return kBase + "[http]\nlisten = \"127.0.0.1:9000\"\ncontrol = \"off\"\nusers_file = \"users\"\n" +
               "viewer_token_file = \"viewer.token\"\nviewer = \"" + viewer + "\"\n[[sink]]\nkind = \"rtsp\"\n" +
               sinkKeys;
    }
    const RtspAccessOptions &access(const DaemonConfig &loaded) const { return loaded.stream.sinks.at(0).rtsp.access; }

    std::filesystem::path folder_;
};

TEST_F(RtspAccessConfig, FollowsHttpViewerByDefault)
{
    const DaemonConfig closed = loadValid(config("credential", ""), folder_.string());
    const std::vector<RtspUser> expected{{"watcher", "see:it"}, {"boss", "c0ntrol"}, {kRtspTokenUser, "viewer-token"}};
    EXPECT_EQ(access(closed).users, expected);
    EXPECT_TRUE(access(closed).certPem.empty());
    EXPECT_TRUE(access(loadValid(config("open", ""), folder_.string())).users.empty());
    EXPECT_TRUE(access(loadValid(kBase + "[[sink]]\nkind = \"rtsp\"\n")).users.empty()); // no [http]: open
}

TEST_F(RtspAccessConfig, CredentialAndNoneOverrideViewer)
{
    EXPECT_EQ(access(loadValid(config("open", "auth = \"credential\"\n"), folder_.string())).users.size(), 3u);
    EXPECT_TRUE(access(loadValid(config("credential", "auth = \"none\"\n"), folder_.string())).users.empty());
}

TEST_F(RtspAccessConfig, ACredentialWithNoneInHttpIsRefused)
{
    const auto problems = loadInvalid(kBase + "[http]\nlisten = \"127.0.0.1:9000\"\ncontrol = \"off\"\n"
                                              "[[sink]]\nkind = \"rtsp\"\nauth = \"credential\"\n");
    EXPECT_TRUE(hasProblem(problems, "sink[0].auth", "nobody could watch")) << formatProblems(problems);
    EXPECT_TRUE(
        hasProblem(loadInvalid(config("open", "auth = \"basic\"\n"), folder_.string()), "sink[0].auth", "basic"));
    EXPECT_TRUE(hasProblem(loadInvalid(config("open", "tls = \"on\"\n"), folder_.string()), "sink[0].tls", "on"));
}

} // namespace
} // namespace overlayd::test
