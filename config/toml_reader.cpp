// TableReader: typed access to a TOML table that records located problems instead of throwing.
#include "config/toml_reader.h"

#include <algorithm>
#include <cmath>

#include "base/utf8.h"

namespace overlayd {

const char *typeName(const toml::node &node)
{
    switch (node.type()) {
    case toml::node_type::table:
        return "a table";
    case toml::node_type::array:
        return "an array";
    case toml::node_type::string:
        return "a string";
    case toml::node_type::integer:
        return "an integer";
    case toml::node_type::floating_point:
        return "a float";
    case toml::node_type::boolean:
        return "a boolean";
    case toml::node_type::date:
        return "a date";
    case toml::node_type::time:
        return "a time";
    case toml::node_type::date_time:
        return "a date-time";
    default:
        return "nothing";
    }
}

TableReader::TableReader(const toml::table &table, std::string path, Problems &problems)
    : table_(&table), path_(std::move(path)), problems_(&problems)
{}

const toml::node *TableReader::node(std::string_view key)
{
    if (std::find(known_.begin(), known_.end(), key) == known_.end())
        known_.emplace_back(key);
    return table_->get(key);
}

std::string TableReader::keyPath(std::string_view key) const
{
    return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

void TableReader::problemAt(const toml::node &at, const std::string &keyPath, std::string message)
{
    const auto &source = at.source();
    // A node read from a drop-in file says so; the loaded file's own nodes carry its name too.
    problems_->add(source.begin.line, source.begin.column, keyPath, std::move(message),
                   source.path && *source.path != problems_->file() ? *source.path : std::string());
}

void TableReader::problem(std::string_view key, std::string message)
{
    if (const toml::node *n = table_->get(key))
        problemAt(*n, keyPath(key), std::move(message));
    else
        problemAt(*table_, keyPath(key), std::move(message));
}

void TableReader::problemAtTable(std::string message)
{
    problemAt(*table_, path_, std::move(message));
}

void TableReader::problemAtPath(std::string_view dottedKey, std::string message)
{
    const toml::node *at = table_;
    for (size_t begin = 0; at && begin <= dottedKey.size();) {
        const size_t end = std::min(dottedKey.find('.', begin), dottedKey.size());
        const toml::table *table = at->as_table();
        const toml::node *next = table ? table->get(dottedKey.substr(begin, end - begin)) : nullptr;
        if (!next)
            break;
        at = next;
        begin = end + 1;
    }
    problemAt(*at, keyPath(dottedKey), std::move(message));
}

std::optional<double> TableReader::numberFrom(const toml::node &n, const std::string &path, Range range)
{
    std::optional<double> value;
    if (const auto *i = n.as_integer())
        value = double(i->get());
    else if (const auto *f = n.as_floating_point())
        value = f->get();
    if (!value) {
        problemAt(n, path, std::string("expected a number, got ") + typeName(n));
        return std::nullopt;
    }
    // A large finite value is out of range like inf is: the message gives the range either way.
    if (!range.contains(*value)) {
        problemAt(n, path, range.refusal(*value));
        return std::nullopt;
    }
    return value;
}

std::optional<double> TableReader::number(std::string_view key, double min, double max)
{
    const toml::node *n = node(key);
    return n ? numberFrom(*n, keyPath(key), Range{min, max}) : std::nullopt;
}

std::optional<double> TableReader::positive(std::string_view key, double max)
{
    const toml::node *n = node(key);
    return n ? numberFrom(*n, keyPath(key), Range{0.0, max, true}) : std::nullopt;
}

std::optional<int64_t> TableReader::integer(std::string_view key, int64_t min, int64_t max)
{
    const toml::node *n = node(key);
    if (!n)
        return std::nullopt;
    const auto *i = n->as_integer();
    if (!i) {
        problemAt(*n, keyPath(key), std::string("expected an integer, got ") + typeName(*n));
        return std::nullopt;
    }
    if (i->get() < min || i->get() > max) {
        problemAt(*n, keyPath(key),
                  "out of range: must be in [" + std::to_string(min) + ", " + std::to_string(max) + "] (got " +
                      std::to_string(i->get()) + ")");
        return std::nullopt;
    }
    return i->get();
}

std::optional<bool> TableReader::boolean(std::string_view key)
{
    const toml::node *n = node(key);
    if (!n)
        return std::nullopt;
    if (const auto *b = n->as_boolean())
        return b->get();
    problemAt(*n, keyPath(key), std::string("expected true or false, got ") + typeName(*n));
    return std::nullopt;
}

std::optional<std::string> TableReader::string(std::string_view key, size_t maxBytes)
{
    const toml::node *n = node(key);
    if (!n)
        return std::nullopt;
    if (const auto *s = n->as_string()) {
        if (s->get().size() > maxBytes) {
            problemAt(*n, keyPath(key),
                      "too long: at most " + std::to_string(maxBytes) + " bytes (got " +
                          std::to_string(s->get().size()) + ")");
            return std::nullopt;
        }
        // toml++ has checked the UTF-8; an escape such as "\u0007" still makes a control character.
        if (const auto problem = outsideTextProblem(s->get(), kConfigStringControls)) {
            problemAt(*n, keyPath(key), *problem);
            return std::nullopt;
        }
        return s->get();
    }
    problemAt(*n, keyPath(key), std::string("expected a string, got ") + typeName(*n));
    return std::nullopt;
}

std::optional<std::string> TableReader::unmatchedChoice(std::string_view key, const std::vector<std::string> &names)
{
    std::string list;
    for (const std::string &name : names)
        list += (list.empty() ? "" : " | ") + name;
    const std::string got = table_->get(key)->as_string()->get();
    std::string message = "unknown value '" + shown(got) + "' (expected " + list + ")";
    if (const std::string guess = closestMatch(got, names); !guess.empty())
        message += "; did you mean '" + guess + "'?";
    problem(key, std::move(message));
    return std::nullopt;
}

void TableReader::ignoreRest()
{
    for (const auto &entry : *table_)
        node(entry.first.str());
}

void TableReader::finish()
{
    for (const auto &[key, value] : *table_) {
        if (std::find(known_.begin(), known_.end(), key.str()) != known_.end())
            continue;
        std::string message = "unknown key '" + shown(key.str()) + "'";
        if (const std::string guess = closestMatch(key.str(), known_); !guess.empty())
            message += "; did you mean '" + guess + "'?";
        const auto &begin = key.source().begin;
        problems_->add(begin.line, begin.column, keyPath(shown(key.str())), std::move(message));
    }
}

} // namespace overlayd