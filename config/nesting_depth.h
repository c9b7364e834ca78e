// SPDX-License-Identifier: Apache-2.0
// A pre-scan of a file's text for how deeply it nests, before a parser that recurses per level sees it:
// cv::FileStorage overflows the stack on a few thousand nested YAML flow sequences or XML elements, toml++ on tens of
// thousands of dotted key parts. The scan is iterative and knows only enough of each syntax to skip strings and
// comments; real files nest a handful of levels, so the limit is far from anything legitimate.
#pragma once

#include <cstddef>
#include <optional>
#include <string_view>

namespace overlayd {

inline constexpr size_t kMaxNestingDepth = 64;

enum class TextSyntax {
    Yaml, // block indentation, "- " items and [ ] { } flow collections
    Xml,  // element depth
    Toml, // arrays and inline tables, plus the parts of a dotted key or a [table.header]
};

struct TooDeep {
    unsigned line = 0, column = 0; // 1-based, where the limit is first passed
};

// Where the text first nests deeper than maxDepth levels; nullopt when it never does.
std::optional<TooDeep> findTooDeep(std::string_view text, TextSyntax syntax, size_t maxDepth = kMaxNestingDepth);

} // namespace overlayd
