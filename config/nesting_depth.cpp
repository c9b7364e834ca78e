// SPDX-License-Identifier: Apache-2.0
// Depth scans for YAML, XML and TOML: one pass each, no recursion, strings and comments skipped.
#include "config/nesting_depth.h"

#include <algorithm>
#include <vector>

namespace overlayd {

namespace {

constexpr size_t npos = std::string_view::npos;

TooDeep positionOf(std::string_view text, size_t offset)
{
    TooDeep at{1, 1};
    for (size_t i = 0; i < offset && i < text.size(); ++i)
        text[i] == '\n' ? (++at.line, at.column = 1) : ++at.column;
    return at;
}

// YAML: the block levels open at a line (its indentation against the enclosing ones, plus one per "- " item
// marker that starts it) plus the flow collections open at a character.
class YamlScan
{
public:
    YamlScan(std::string_view text, size_t maxDepth) : text_(text), max_(maxDepth) {}

    std::optional<size_t> run()
    {
        for (size_t start = 0; start < text_.size();) {
            const size_t end = std::min(text_.find('\n', start), text_.size());
            if (auto at = line(start, end))
                return at;
            start = end + 1;
        }
        return std::nullopt;
    }

private:
    std::optional<size_t> line(size_t start, size_t end)
    {
        size_t i = start;
        while (i < end && text_[i] == ' ')
            ++i;
        if (quote_ == 0 && flow_ == 0 && i < end && text_[i] != '#' && text_[i] != '\r') {
            const size_t indent = i - start;
            while (!indents_.empty() && indents_.back() > indent)
                indents_.pop_back();
            if (indents_.empty() || indents_.back() < indent)
                indents_.push_back(indent);
            block_ = indents_.size();
            for (size_t j = i; j < end && text_[j] == '-' && (j + 1 == end || text_[j + 1] == ' ');) {
                ++block_;
                for (++j; j < end && text_[j] == ' ';)
                    ++j;
            }
            if (block_ > max_)
                return i;
        }
        word_ = false;
        for (size_t j = start; j < end; ++j)
            if (auto at = character(j, j == start ? ' ' : text_[j - 1]))
                return at;
        return std::nullopt;
    }

    // One character. In block context a bracket or quote opens something only where a token starts, not inside a
    // plain word ("name: x[0]"), which word_ tracks; the scan errs towards counting a level.
    std::optional<size_t> character(size_t &j, char prev)
    {
        const char c = text_[j];
        if (quote_ != 0) {
            if (quote_ == '"' && c == '\\')
                ++j;
            else if (c == quote_ && quote_ == '\'' && j + 1 < text_.size() && text_[j + 1] == '\'')
                ++j;
            else if (c == quote_)
                quote_ = 0;
            return std::nullopt;
        }
        if (c == '#' && (prev == ' ' || prev == '\t')) {
            j = std::min(text_.find('\n', j), text_.size()) - 1; // the rest of the line is a comment
        } else if (std::string_view(" \t,:-?").find(c) != npos) {
            word_ = false;
        } else if ((c == '[' || c == '{') && (!word_ || flow_ > 0)) { // a flow scalar cannot hold brackets
            if (block_ + ++flow_ > max_)
                return j;
        } else if ((c == ']' || c == '}') && flow_ > 0) {
            --flow_;
        } else if ((c == '"' || c == '\'') && !word_) {
            quote_ = c;
        } else {
            word_ = true;
        }
        return std::nullopt;
    }

    std::string_view text_;
    size_t max_;
    std::vector<size_t> indents_;
    size_t block_ = 0, flow_ = 0;
    char quote_ = 0;
    bool word_ = false;
};

// XML: open elements; comments, CDATA, declarations and processing instructions do not nest.
std::optional<size_t> scanXml(std::string_view text, size_t maxDepth)
{
    size_t depth = 0;
    for (size_t i = text.find('<'); i != npos; i = text.find('<', i + 1)) {
        const std::string_view rest = text.substr(i);
        size_t end = npos;
        if (rest.starts_with("<!--"))
            end = text.find("-->", i + 4);
        else if (rest.starts_with("<![CDATA["))
            end = text.find("]]>", i + 9);
        else if (rest.starts_with("<?"))
            end = text.find("?>", i + 2);
        else if (rest.starts_with("<!") || rest.starts_with("</")) {
            end = text.find('>', i + 2);
            depth -= rest[1] == '/' && depth > 0 ? 1 : 0;
        } else {
            char quote = 0;
            for (end = i + 1; end < text.size() && (quote != 0 || text[end] != '>'); ++end)
                if (text[end] == '"' || text[end] == '\'')
                    quote = quote == 0 ? text[end] : quote == text[end] ? 0 : quote;
            if (end == text.size())
                return std::nullopt; // cut short: the parser says so
            if (text[end - 1] != '/' && ++depth > maxDepth)
                return i;
        }
        if (end == npos)
            return std::nullopt;
        i = end;
    }
    return std::nullopt;
}

// TOML: open arrays and inline tables, plus the parts of the key being read and of the table header above it.
std::optional<size_t> scanToml(std::string_view text, size_t maxDepth)
{
    std::vector<char> open;
    bool key = true, header = false;
    size_t parts = 1, headerParts = 0;
    for (size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (c == '\n') {
            if (header)
                headerParts = parts;
            if (open.empty())
                key = true, header = false, parts = 1;
        } else if (c == '#') {
            i = std::min(text.find('\n', i), text.size()) - 1;
        } else if (c == '"' || c == '\'') {
            const std::string_view triple = c == '"' ? "\"\"\"" : "'''";
            const bool multiLine = text.substr(i, 3) == triple;
            size_t j = i + (multiLine ? 3 : 1);
            for (; j < text.size(); ++j) {
                if (c == '"' && text[j] == '\\')
                    ++j;
                else if (multiLine ? text.substr(j, 3) == triple : text[j] == c || text[j] == '\n')
                    break;
            }
            i = multiLine ? j + 2 : j - (j < text.size() && text[j] == '\n' ? 1 : 0);
        } else if (key) {
            if (c == '[' && open.empty())
                header = true, parts = 1;
            else if (c == '.' && (header ? 0 : headerParts) + open.size() + ++parts > maxDepth)
                return i;
            else if (c == '=')
                key = false;
            else if (c == '}' && !open.empty())
                open.pop_back(), key = false;
        } else if (c == '[' || c == '{') {
            open.push_back(c);
            if (headerParts + open.size() > maxDepth)
                return i;
            if (c == '{')
                key = true, parts = 1;
        } else if ((c == ']' || c == '}') && !open.empty()) {
            open.pop_back();
        } else if (c == ',' && !open.empty() && open.back() == '{') {
            key = true, parts = 1;
        }
    }
    return std::nullopt;
}

} // namespace

std::optional<TooDeep> findTooDeep(std::string_view text, TextSyntax syntax, size_t maxDepth)
{
    std::optional<size_t> offset;
    switch (syntax) {
    case TextSyntax::Yaml:
        offset = YamlScan(text, maxDepth).run();
        break;
    case TextSyntax::Xml:
        offset = scanXml(text, maxDepth);
        break;
    case TextSyntax::Toml:
        offset = scanToml(text, maxDepth);
        break;
    }
    if (!offset)
        return std::nullopt;
    return positionOf(text, *offset);
}

} // namespace overlayd
