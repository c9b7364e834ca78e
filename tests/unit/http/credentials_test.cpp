// SPDX-License-Identifier: Apache-2.0
// Credentials: bearer tokens and basic users give their roles, anything else none; which role a request needs; the
// users file's refusals name the line and never the password.
#include "http/credentials.h"

#include <filesystem>
#include <fstream>
#include <unistd.h>

#include <gtest/gtest.h>

using namespace overlayd;

namespace {

std::string file(const std::string &name, const std::string &text)
{
    const std::filesystem::path path =
        std::filesystem::temp_directory_path() / ("overlayd-credentials-" + std::to_string(::getpid()) + "-" + name);
    std::ofstream(path) << text;
    return path.string();
}

} // namespace

TEST(Credentials, TokensAndUsersGiveTheirRoles)
{
    HttpOptions options;
    options.tokenFile = file("control", "control-secret\n");
    options.viewerTokenFile = file("viewer", "viewer-secret\n");
    options.usersFile = file("users", "# users\nalice:viewer:a:b\nbob:control:pw\n");
    const auto credentials = Credentials::load(options);
    ASSERT_TRUE(credentials) << credentials.error().message;
    EXPECT_EQ(credentials->fromHeader("Bearer control-secret"), Role::Control);
    EXPECT_EQ(credentials->fromHeader("Bearer viewer-secret"), Role::Viewer);
    EXPECT_EQ(credentials->fromHeader("Bearer viewer-secre"), Role::None);
    EXPECT_EQ(credentials->fromHeader("Bearer "), Role::None);
    EXPECT_EQ(credentials->fromHeader("Basic YWxpY2U6YTpi"), Role::Viewer); // alice:a:b
    EXPECT_EQ(credentials->fromHeader("Basic Ym9iOnB3"), Role::Control);    // bob:pw
    EXPECT_EQ(credentials->fromHeader("Basic Ym9iOnB4"), Role::None);       // bob:px
    EXPECT_EQ(credentials->fromHeader("Basic !!!"), Role::None);
    EXPECT_EQ(credentials->fromHeader("Digest x"), Role::None);
}

TEST(Credentials, DigestLooksTheUserUpByNameOnly)
{
    HttpOptions options;
    options.usersFile = file("digest-users", "alice:viewer:a:b\nbob:control:pw\n");
    const auto credentials = Credentials::load(options);
    ASSERT_TRUE(credentials) << credentials.error().message;
    const BasicUser *bob = credentials->user("bob");
    ASSERT_NE(bob, nullptr);
    EXPECT_EQ(bob->password, "pw");
    EXPECT_EQ(bob->role, Role::Control);
    EXPECT_EQ(credentials->user("alice")->password, "a:b");
    EXPECT_EQ(credentials->user("bo"), nullptr);
    EXPECT_EQ(credentials->user(""), nullptr);
}

TEST(Credentials, WhatARequestNeeds)
{
    EXPECT_EQ(requiredRole("GET", "/stream"), Role::Viewer);
    EXPECT_EQ(requiredRole("HEAD", "/"), Role::Viewer);
    EXPECT_EQ(requiredRole("POST", "/api/unproject"), Role::Viewer);
    EXPECT_EQ(requiredRole("POST", "/api/save"), Role::Control);
    EXPECT_EQ(requiredRole("POST", "/whep"), Role::Viewer); // WHEP is watching, as /stream is
    EXPECT_EQ(requiredRole("DELETE", "/whep/3"), Role::Viewer);
    EXPECT_EQ(requiredRole("DELETE", "/api/camera"), Role::Control);
    EXPECT_EQ(requiredRole("PUT", "/api/camera"), Role::Control);
}

TEST(Credentials, TheUsersFileIsRefusedByLineWithoutThePassword)
{
    const auto role = readUsersFile(file("badrole", "alice:viewer:x\n\nbob:admin:hunter2\n"));
    ASSERT_FALSE(role);
    EXPECT_NE(role.error().message.find("line 3"), std::string::npos) << role.error().message;
    EXPECT_EQ(role.error().message.find("hunter2"), std::string::npos) << role.error().message;
    EXPECT_FALSE(readUsersFile(file("short", "bob:control\n")));
    EXPECT_FALSE(readUsersFile(file("empty", "bob:control:\n")));
    EXPECT_FALSE(readUsersFile("/nonexistent/users"));
}
