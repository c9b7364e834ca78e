// SPDX-License-Identifier: Apache-2.0
// Credentials: who may watch and who may change. A viewer credential opens the page, /stream, /snapshot, /state,
// /metrics and the ground points (/api/project, /api/unproject); a control credential opens those and every change
// and save. Each is a bearer token (a token file) or an HTTP basic user (users_file); every secret is compared in
// time that does not depend on where it differs, and none is ever logged.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "base/result.h"
#include "http/http_options.h"

namespace overlayd {

enum class Role { None, Viewer, Control };

// What a request needs: reading anything and asking for ground points is viewing; everything else is a change.
Role requiredRole(std::string_view method, std::string_view path);

struct BasicUser {
    std::string name, password;
    Role role = Role::Viewer;
};

// users_file: one user a line, "NAME:ROLE:PASSWORD" (ROLE viewer or control; the password is the rest of the line,
// colons and all); blank lines and lines starting with '#' skipped. At most kMaxUsers users; each field within
// kMaxTokenBytes. The error names the file and line (never the password).
Result<std::vector<BasicUser>> readUsersFile(const std::string &path);

class Credentials
{
public:
    // The token files and users file the options name, read by their own readers (as check-config read them).
    static Result<Credentials> load(const HttpOptions &options);

    // The role an Authorization header proves ("Bearer TOKEN" or "Basic base64(NAME:PASSWORD)"); None for any
    // other.
    Role fromHeader(std::string_view authorization) const;
    Role bearer(std::string_view token) const;
    Role basic(std::string_view name, std::string_view password) const;
    bool hasUsers() const { return !users_.empty(); }
    // The users_file user of that name (for a Digest answer, which libmicrohttpd checks against its password), or
    // null.
    const BasicUser *user(std::string_view name) const;

private:
    std::string controlToken_, viewerToken_;
    std::vector<BasicUser> users_;
};

} // namespace overlayd
