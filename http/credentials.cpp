// SPDX-License-Identifier: Apache-2.0
// Credentials: the users file's reader, the tokens and users compared in constant time, and which role a request
// needs.
#include "http/credentials.h"

#include <algorithm>
#include <cstring>
#include <optional>
#include <sstream>

#include "base/regular_file.h"
#include "http/token_file.h"

namespace overlayd {

namespace {

// Equal strings in time that depends on neither where they differ nor (beyond the given one's length) the expected
// one's length.
bool sameSecret(std::string_view given, std::string_view expected)
{
    unsigned char difference = given.size() == expected.size() ? 0 : 1;
    for (size_t i = 0; i < given.size(); ++i)
        difference |= static_cast<unsigned char>(given[i] ^ expected[i % std::max<size_t>(expected.size(), 1)]);
    return difference == 0 && !expected.empty();
}

// RFC 4648 base64 (padding optional); nullopt for anything else.
std::optional<std::string> base64Decoded(std::string_view text)
{
    std::string out;
    unsigned buffer = 0, bits = 0;
    for (const char c : text) {
        if (c == '=')
            break;
        const char *alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        const char *found = c ? std::strchr(alphabet, c) : nullptr;
        if (!found)
            return std::nullopt;
        buffer = (buffer << 6) | unsigned(found - alphabet);
        bits += 6;
        if (bits >= 8) {
            bits -= 8;
            out.push_back(char((buffer >> bits) & 0xff));
        }
    }
    return out;
}

Role stronger(Role a, Role b)
{
    return int(a) > int(b) ? a : b;
}

} // namespace

Role requiredRole(std::string_view method, std::string_view path)
{
    if (method == "GET" || method == "HEAD")
        return Role::Viewer;
    if (method == "POST" && (path == "/api/project" || path == "/api/unproject"))
        return Role::Viewer;
    // WHEP: watching over WebRTC, as /stream does over MJPEG (the offer, then the hang-up)
    if ((method == "POST" && path == "/whep") || (method == "DELETE" && path.starts_with("/whep/")))
        return Role::Viewer;
    return Role::Control;
}

Result<std::vector<BasicUser>> readUsersFile(const std::string &path)
{
    // Every user's longest line, and as many comment lines again.
    auto text = readRegularFile(path, 2 * kMaxUsers * (3 * kMaxTokenBytes + 2));
    if (!text)
        return makeError(text.error().code, "cannot read '" + path + "': " + text.error().message);
    std::istringstream in(*text);
    std::vector<BasicUser> users;
    std::string line;
    for (unsigned number = 1; std::getline(in, line); ++number) {
        const std::string where = "'" + path + "' line " + std::to_string(number) + ": ";
        if (line.size() > 3 * kMaxTokenBytes)
            return makeError(ErrorCode::InvalidArgument, where + "too long");
        if (!line.empty() && line.back() == '\r')
            line.pop_back();
        if (line.empty() || line[0] == '#')
            continue;
        const size_t first = line.find(':'), second = first == std::string::npos ? first : line.find(':', first + 1);
        if (second == std::string::npos)
            return makeError(ErrorCode::InvalidArgument, where + "not NAME:ROLE:PASSWORD");
        BasicUser user{line.substr(0, first), line.substr(second + 1), Role::None};
        const std::string role = line.substr(first + 1, second - first - 1);
        user.role = role == "viewer" ? Role::Viewer : role == "control" ? Role::Control : Role::None;
        if (user.role == Role::None)
            return makeError(ErrorCode::InvalidArgument, where + "the role '" + role + "' is not viewer or control");
        if (user.name.empty() || user.password.empty() || user.name.size() > kMaxTokenBytes ||
            user.password.size() > kMaxTokenBytes)
            return makeError(ErrorCode::InvalidArgument, where + "the name and the password must each hold 1 to " +
                                                             std::to_string(kMaxTokenBytes) + " bytes");
        if (users.size() == kMaxUsers)
            return makeError(ErrorCode::InvalidArgument, where + "more than " + std::to_string(kMaxUsers) + " users");
        users.push_back(std::move(user));
    }
    return users;
}

Result<Credentials> Credentials::load(const HttpOptions &options)
{
    Credentials out;
    if (!options.tokenFile.empty() && options.control == ControlMode::Token) {
        auto token = readTokenFile(options.tokenFile);
        if (!token)
            return makeError(token.error().code, "http.token_file " + token.error().message);
        out.controlToken_ = *token;
    }
    if (!options.viewerTokenFile.empty()) {
        auto token = readTokenFile(options.viewerTokenFile);
        if (!token)
            return makeError(token.error().code, "http.viewer_token_file " + token.error().message);
        out.viewerToken_ = *token;
    }
    if (!options.usersFile.empty()) {
        auto users = readUsersFile(options.usersFile);
        if (!users)
            return makeError(users.error().code, "http.users_file " + users.error().message);
        out.users_ = std::move(*users);
    }
    return out;
}

Role Credentials::fromHeader(std::string_view authorization) const
{
    constexpr std::string_view kBearer = "Bearer ", kBasic = "Basic ";
    if (authorization.substr(0, kBearer.size()) == kBearer)
        return bearer(authorization.substr(kBearer.size()));
    if (authorization.substr(0, kBasic.size()) != kBasic || authorization.size() > 4 * kMaxTokenBytes)
        return Role::None;
    const auto pair = base64Decoded(authorization.substr(kBasic.size()));
    const size_t colon = pair ? pair->find(':') : std::string::npos;
    if (colon == std::string::npos)
        return Role::None;
    return basic(std::string_view(*pair).substr(0, colon), std::string_view(*pair).substr(colon + 1));
}

Role Credentials::bearer(std::string_view token) const
{
    // Both compared whatever the first gives, so that the time says nothing about which one matched.
    const bool control = sameSecret(token, controlToken_);
    const bool viewer = sameSecret(token, viewerToken_);
    return control ? Role::Control : viewer ? Role::Viewer : Role::None;
}

const BasicUser *Credentials::user(std::string_view name) const
{
    const BasicUser *found = nullptr;
    for (const BasicUser &user : users_)
        if (sameSecret(name, user.name) && found == nullptr)
            found = &user;
    return found;
}

Role Credentials::basic(std::string_view name, std::string_view password) const
{
    Role role = Role::None;
    for (const BasicUser &user : users_) {
        const bool nameMatches = sameSecret(name, user.name);
        const bool passwordMatches = sameSecret(password, user.password);
        if (nameMatches && passwordMatches)
            role = stronger(role, user.role);
    }
    return role;
}

} // namespace overlayd
