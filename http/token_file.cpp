// SPDX-License-Identifier: Apache-2.0
// readTokenFile: the one reader of http.token_file, for the config loader and the server alike.
#include "http/token_file.h"

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "http/http_options.h"

namespace overlayd {

namespace {

constexpr size_t kReadBytes = 16 * kMaxTokenBytes;

} // namespace

Result<std::string> readTokenFile(const std::string &path)
{
    std::error_code error;
    std::ifstream in;
    if (std::filesystem::is_regular_file(path, error))
        in.open(path, std::ios::binary);
    if (!in.is_open())
        return makeError(ErrorCode::NotFound, "cannot read '" + path +
                                                  "' (control = \"token\" needs a readable "
                                                  "regular file that holds the token)");
    // The first line, read within a bound (blanks may follow the token); a longer one is refused as too long.
    std::string token(kReadBytes, '\0');
    in.read(token.data(), std::streamsize(token.size()));
    token.resize(size_t(in.gcount()));
    const bool cut = token.find('\n') == std::string::npos && token.size() == kReadBytes;
    token.resize(std::min(token.find('\n'), token.size()));
    while (!token.empty() && (token.back() == '\r' || token.back() == ' ' || token.back() == '\t'))
        token.pop_back();
    if (token.empty() || token.size() > kMaxTokenBytes || cut)
        return makeError(ErrorCode::InvalidArgument,
                         std::string(token.empty() ? "empty" : "too long") + ": the first line of '" + path +
                             "' must hold the token (1 to " + std::to_string(kMaxTokenBytes) + " bytes)");
    return token;
}

} // namespace overlayd
