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

// The installed page folder (the build tree's http/www unless the package set another).
std::string defaultPageDirectory();

} // namespace overlayd