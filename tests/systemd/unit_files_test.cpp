// SPDX-License-Identifier: Apache-2.0
// The installed units, checked by systemd's own tools: systemd-analyze verify and security, and systemd-sysusers.
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <iostream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "notify_socket.h"

namespace overlayd {
namespace {

namespace fs = std::filesystem;

struct Output {
    int status = -1;
    std::string text; // stdout and stderr together
};

Output run(const std::string &command)
{
    Output output;
    FILE *pipe = popen((command + " 2>&1").c_str(), "r");
    if (!pipe)
        return output;
    std::array<char, 4096> buffer{};
    for (size_t n; (n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0;)
        output.text.append(buffer.data(), n);
    output.status = pclose(pipe);
    return output;
}

std::string readFile(const fs::path &path)
{
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

// ExecStart must name an executable that exists, or verify fails: the built overlayd when there is one, /bin/true
// before the daemon target exists (verify only checks that the command is executable, it does not run it).
std::string testBinary()
{
    std::string built = OVERLAYD_BINARY;
    return built.empty() ? "/bin/true" : built;
}

// A temp copy of the unit as `cmake --install` writes it, with the binary path substituted and renamed (the
// template becomes the instance overlayd@demo.service, which is what systemd would load).
fs::path stageUnit(const test::TempDir &dir, const std::string &unit, const std::string &as)
{
    std::string text = readFile(fs::path(OVERLAYD_CONFIGURED_UNIT_DIR) / unit);
    std::string installed = OVERLAYD_INSTALLED_BINARY;
    for (size_t at; (at = text.find(installed)) != std::string::npos;)
        text.replace(at, installed.size(), testBinary());
    fs::path staged = dir.path() / as;
    std::ofstream(staged) << text;
    return staged;
}

const std::map<std::string, std::string> units = {{"overlayd.service", "overlayd.service"},
                                                  {"overlayd@.service", "overlayd@demo.service"},
                                                  {"overlayd-http@.service", "overlayd-http@demo.service"}};

TEST(UnitFiles, InstalledUnitsAreConfigured)
{
    for (const auto &[unit, as] : units) {
        std::string text = readFile(fs::path(OVERLAYD_CONFIGURED_UNIT_DIR) / unit);
        ASSERT_FALSE(text.empty()) << unit;
        EXPECT_EQ(text.find('@' + std::string("OVERLAYD_")), std::string::npos) << unit << ": unsubstituted variable";
        EXPECT_NE(text.find("ExecStart=" + std::string(OVERLAYD_INSTALLED_BINARY) + " run --config "),
                  std::string::npos)
            << unit;
    }
}

TEST(UnitFiles, SystemdAnalyzeVerifyIsSilent)
{
    test::TempDir dir;
    std::cout << "ExecStart points at " << testBinary() << "\n";
    for (const auto &[unit, as] : units) {
        fs::path staged = stageUnit(dir, unit, as);
        Output verify = run(std::string(SYSTEMD_ANALYZE) + " verify --man=no '" + staged.string() + "'");
        // verify exits 0 on unknown keys and unparsable values (it only warns), so any output is a failure too.
        EXPECT_EQ(verify.status, 0) << as << ":\n" << verify.text;
        EXPECT_EQ(verify.text, "") << as;
    }
}

TEST(UnitFiles, SecurityExposureAtMostTwo)
{
    test::TempDir dir;
    for (const auto &[unit, as] : units) {
        fs::path staged = stageUnit(dir, unit, as);
        Output security = run(std::string(SYSTEMD_ANALYZE) + " security --offline=true --man=no --no-pager '" +
                              staged.string() + "'");
        std::smatch match;
        std::regex overall("Overall exposure level for [^:]+: ([0-9]+\\.[0-9]) ([A-Z]+)");
        ASSERT_TRUE(std::regex_search(security.text, match, overall)) << security.text;
        double exposure = std::stod(match[1]);
        std::cout << as << ": systemd-analyze security exposure " << match[1] << " " << match[2] << "\n";
        // 2.0 ("OK" or better) for every unit, the one that opens the HTTP(S) port included.
        EXPECT_LE(exposure, 2.0) << security.text;
    }
}

// [Service] lines without comments, minus the ones that name the instance.
std::multiset<std::string> serviceSettings(const std::string &unit)
{
    std::multiset<std::string> settings;
    std::istringstream lines(readFile(fs::path(OVERLAYD_UNIT_SOURCE_DIR) / unit));
    bool inService = false;
    for (std::string line; std::getline(lines, line);) {
        if (!line.empty() && line[0] == '[')
            inService = line == "[Service]";
        else if (inService && !line.empty() && line[0] != '#')
            settings.insert(line);
    }
    for (const char *perInstance : {"ExecStart=", "StateDirectory=", "RuntimeDirectory=", "WorkingDirectory="})
        std::erase_if(settings, [&](const std::string &s) { return s.rfind(perInstance, 0) == 0; });
    return settings;
}

TEST(UnitFiles, TemplateAndSingleUnitShareTheHardening)
{
    auto single = serviceSettings("overlayd.service");
    EXPECT_GT(single.size(), 30u);
    EXPECT_EQ(single, serviceSettings("overlayd@.service"));
}

TEST(UnitFiles, SysusersCreatesTheUserInVideoAndGpio)
{
    test::TempDir root;
    fs::create_directories(root.path() / "etc");
    std::ofstream(root.path() / "etc/passwd") << "root:x:0:0:root:/root:/bin/sh\n";
    std::ofstream(root.path() / "etc/group") << "root:x:0:\nvideo:x:44:\n";
    Output sysusers = run(std::string(SYSTEMD_SYSUSERS) + " --root='" + root.path().string() + "' '" +
                          OVERLAYD_UNIT_SOURCE_DIR + "/overlayd.sysusers'");
    ASSERT_EQ(sysusers.status, 0) << sysusers.text;
    std::string group = readFile(root.path() / "etc/group");
    EXPECT_NE(group.find("video:x:44:overlayd\n"), std::string::npos) << group;
    EXPECT_TRUE(std::regex_search(group, std::regex("(^|\n)gpio:x:[0-9]+:overlayd\n"))) << group;
    std::string passwd = readFile(root.path() / "etc/passwd");
    EXPECT_TRUE(
        std::regex_search(passwd, std::regex("\noverlayd:x:[0-9]+:[0-9]+:[^:]*:/var/lib/overlayd:[^:]*nologin")))
        << passwd;
}

} // namespace
} // namespace overlayd
