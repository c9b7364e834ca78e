// SPDX-License-Identifier: Apache-2.0
#include "http/page_files.h"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string_view>

namespace overlayd {

namespace {

constexpr size_t kMaxPageFileBytes = 4 * 1024 * 1024;

struct Kind {
    std::string_view extension;
    const char *contentType;
};
constexpr Kind kKinds[] = {
    {".html", "text/html; charset=utf-8"},
    {".js", "text/javascript; charset=utf-8"},
    {".css", "text/css; charset=utf-8"},
    {".png", "image/png"},
    {".svg", "image/svg+xml"},
    {".ico", "image/x-icon"},
};

bool plainName(std::string_view name)
{
    if (name.empty() || name.front() == '.')
        return false;
    for (const char c : name)
        if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '_' ||
              c == '.'))
            return false;
    return name.find("..") == std::string_view::npos;
}

} // namespace

std::optional<PageFile> readPageFile(const std::string &directory, const std::string &urlPath)
{
    const std::string name = urlPath == "/" ? "index.html" : urlPath.substr(urlPath.empty() ? 0 : 1);
    if (!plainName(name))
        return std::nullopt;
    const Kind *kind = nullptr;
    for (const Kind &k : kKinds)
        if (name.size() > k.extension.size() && name.ends_with(k.extension))
            kind = &k;
    if (!kind)
        return std::nullopt;
    std::ifstream in(directory + "/" + name, std::ios::binary);
    if (!in)
        return std::nullopt;
    std::ostringstream text;
    text << in.rdbuf();
    if (text.str().size() > kMaxPageFileBytes)
        return std::nullopt;
    return PageFile{kind->contentType, text.str()};
}

std::string defaultPageDirectory()
{
    // An installed binary (a package's /usr/bin/overlayd, built in a tree elsewhere) finds the page in its prefix's
    // share/overlayd/www; a binary in the build tree has none there and takes the folder it was built with.
    std::error_code error;
    const std::filesystem::path binary = std::filesystem::read_symlink("/proc/self/exe", error);
    if (!error) {
        const std::filesystem::path installed = binary.parent_path().parent_path() / "share/overlayd/www";
        if (std::filesystem::is_directory(installed, error))
            return installed.string();
    }
    return OVERLAYD_PAGE_DIRECTORY;
}

} // namespace overlayd
