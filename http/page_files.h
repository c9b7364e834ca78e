// SPDX-License-Identifier: Apache-2.0
// The alignment page's files: only plain names of the known kinds, straight from one folder (no listing, no
// subfolders, nothing reached through "..").
#pragma once

#include <optional>
#include <string>

namespace overlayd {

struct PageFile {
    std::string contentType;
    std::string body;
};

// "/" is index.html. nullopt when the path is not a page file or the file does not exist.
std::optional<PageFile> readPageFile(const std::string &directory, const std::string &urlPath);

// The page folder: PREFIX/share/overlayd/www beside an installed PREFIX/bin/overlayd, else the one built in (the
// source tree's http/www unless the build set OVERLAYD_PAGE_DIRECTORY).
std::string defaultPageDirectory();

} // namespace overlayd
