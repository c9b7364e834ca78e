// SPDX-License-Identifier: Apache-2.0
// TableReader: typed access to a TOML table that records located problems instead of throwing; the compound values
// (quaternions, number lists, points, colours, nested tables) after the scalars.
#include "config/toml_reader.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <string>

#include "base/utf8.h"
#include "config/limits.h"

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
        std::string_view part = dottedKey.substr(begin, end - begin);
        // "sink[2]": the third entry of an array of tables.
        size_t index = std::string_view::npos;
        if (const size_t open = part.find('['); open != std::string_view::npos && part.ends_with(']')) {
            const std::string_view digits = part.substr(open + 1, part.size() - open - 2);
            if (std::from_chars(digits.data(), digits.data() + digits.size(), index).ptr !=
                digits.data() + digits.size())
                index = std::string_view::npos;
            part = part.substr(0, open);
        }
        const toml::table *table = at->as_table();
        const toml::node *next = table ? table->get(part) : nullptr;
        if (next && index != std::string_view::npos) {
            const toml::array *array = next->as_array();
            next = array && index < array->size() ? array->get(index) : nullptr;
        }
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

// TableReader's compound values: quaternions, number lists, points, colours and nested tables.

namespace {

struct NamedColour {
    std::string_view name;
    Rgba colour;
};
constexpr NamedColour kNamedColours[] = {
    {"white", {255, 255, 255, 255}}, {"black", {0, 0, 0, 255}},       {"red", {255, 0, 0, 255}},
    {"green", {0, 255, 0, 255}},     {"blue", {0, 0, 255, 255}},      {"yellow", {255, 255, 0, 255}},
    {"cyan", {0, 255, 255, 255}},    {"magenta", {255, 0, 255, 255}}, {"orange", {255, 165, 0, 255}},
};

std::optional<Rgba> parseHexColour(std::string_view text)
{
    if ((text.size() != 7 && text.size() != 9) || text[0] != '#')
        return std::nullopt;
    uint8_t bytes[4] = {0, 0, 0, 255};
    for (size_t i = 1; i < text.size(); i += 2) {
        const std::string pair(text.substr(i, 2));
        if (!std::isxdigit(static_cast<unsigned char>(pair[0])) || !std::isxdigit(static_cast<unsigned char>(pair[1])))
            return std::nullopt;
        bytes[i / 2] = uint8_t(std::stoul(pair, nullptr, 16));
    }
    return Rgba{bytes[0], bytes[1], bytes[2], bytes[3]};
}

} // namespace

std::optional<glm::dquat> TableReader::quaternion(std::string_view key)
{
    const auto wxyz = vector<glm::dvec4, 4>(key, kAnyMagnitude);
    if (!wxyz)
        return std::nullopt;
    const glm::dquat q(wxyz->x, wxyz->y, wxyz->z, wxyz->w);
    const double norm = glm::length(q);
    if (norm < 1e-9) {
        problem(key, "a rotation quaternion [w, x, y, z] must not be zero");
        return std::nullopt;
    }
    return q / norm;
}

bool TableReader::withinCount(const toml::array &array, const std::string &path, size_t maxCount, const char *what)
{
    if (array.size() <= maxCount)
        return true;
    problemAt(*array.get(maxCount), path + "[" + std::to_string(maxCount) + "]",
              "too many " + std::string(what) + ": at most " + std::to_string(maxCount) + " (got " +
                  std::to_string(array.size()) + ")");
    return false;
}

std::optional<std::vector<double>> TableReader::numbers(std::string_view key, size_t maxCount, Range range)
{
    const toml::node *n = node(key);
    if (!n)
        return std::nullopt;
    const toml::array *array = n->as_array();
    if (!array) {
        problemAt(*n, keyPath(key), std::string("expected an array of numbers, got ") + typeName(*n));
        return std::nullopt;
    }
    if (!withinCount(*array, keyPath(key), maxCount, "numbers"))
        return std::nullopt;
    std::vector<double> out;
    for (size_t i = 0; i < array->size(); ++i) {
        const auto value = numberFrom(*array->get(i), keyPath(key) + "[" + std::to_string(i) + "]", range);
        if (!value)
            return std::nullopt;
        out.push_back(*value);
    }
    return out;
}

std::optional<std::vector<std::string>> TableReader::strings(std::string_view key, size_t maxCount)
{
    const toml::node *n = node(key);
    if (!n)
        return std::nullopt;
    const toml::array *array = n->as_array();
    if (!array) {
        problemAt(*n, keyPath(key), std::string("expected an array of strings, got ") + typeName(*n));
        return std::nullopt;
    }
    if (array->size() > maxCount) {
        problemAt(*n, keyPath(key),
                  "at most " + std::to_string(maxCount) + " entries, got " + std::to_string(array->size()));
        return std::nullopt;
    }
    std::vector<std::string> out;
    for (size_t i = 0; i < array->size(); ++i) {
        const toml::node &entry = *array->get(i);
        if (!entry.is_string()) {
            problemAt(entry, keyPath(key) + "[" + std::to_string(i) + "]",
                      std::string("expected a string, got ") + typeName(entry));
            return std::nullopt;
        }
        out.push_back(*entry.value<std::string>());
    }
    return out;
}

std::optional<std::vector<glm::dvec3>> TableReader::points(std::string_view key, size_t maxCount, Range range)
{
    return points(key, maxCount, range, nullptr);
}

std::optional<std::vector<glm::dvec3>> TableReader::points(std::string_view key, size_t maxCount, Range range,
                                                           bool *screen)
{
    const toml::node *n = node(key);
    if (!n)
        return std::nullopt;
    const toml::array *array = n->as_array();
    if (!array) {
        problemAt(*n, keyPath(key), std::string("expected an array of [x, y, z] points, got ") + typeName(*n));
        return std::nullopt;
    }
    if (!withinCount(*array, keyPath(key), maxCount, "points"))
        return std::nullopt;
    std::vector<glm::dvec3> out;
    for (size_t i = 0; i < array->size(); ++i) {
        const toml::node &element = *array->get(i);
        const std::string path = keyPath(key) + "[" + std::to_string(i) + "]";
        const toml::array *xyz = element.as_array();
        const size_t size = xyz ? xyz->size() : 0;
        if (screen && i == 0 && size == 2)
            *screen = true;
        else if (screen && i == 0)
            *screen = false;
        const size_t wanted = screen && *screen ? 2 : 3;
        if (size != wanted) {
            const char *expected = !screen       ? "an [x, y, z] point"
                                   : i == 0      ? "an [x, y] or [x, y, z] point"
                                   : wanted == 2 ? "an [x, y] point like the first"
                                                 : "an [x, y, z] point like the first";
            problemAt(element, path, std::string("expected ") + expected + ", got " + typeName(element));
            return std::nullopt;
        }
        glm::dvec3 point(0.0);
        for (size_t c = 0; c < wanted; ++c) {
            const auto value = numberFrom(*xyz->get(c), path + "[" + std::to_string(c) + "]", range);
            if (!value)
                return std::nullopt;
            point[int(c)] = *value;
        }
        out.push_back(point);
    }
    return out;
}

std::optional<Rgba> TableReader::colourFrom(const toml::node &n, const std::string &path)
{
    if (const auto *s = n.as_string()) {
        for (const NamedColour &named : kNamedColours)
            if (named.name == s->get())
                return named.colour;
        if (const auto hex = parseHexColour(s->get()))
            return hex;
        problemAt(n, path, "not a colour: '" + s->get() + "' (expected \"#rrggbb\", \"#rrggbbaa\" or a name)");
        return std::nullopt;
    }
    const toml::array *array = n.as_array();
    if (!array || array->size() < 3 || array->size() > 4) {
        problemAt(n, path, std::string("expected a colour (\"#rrggbb\" or [r, g, b, a]), got ") + typeName(n));
        return std::nullopt;
    }
    uint8_t channels[4] = {0, 0, 0, 255};
    for (size_t i = 0; i < array->size(); ++i) {
        const auto *value = array->get(i)->as_integer();
        if (!value || value->get() < 0 || value->get() > 255) {
            problemAt(*array->get(i), path, "colour components must be integers in [0, 255]");
            return std::nullopt;
        }
        channels[i] = uint8_t(value->get());
    }
    return Rgba{channels[0], channels[1], channels[2], channels[3]};
}

std::optional<Rgba> TableReader::colour(std::string_view key)
{
    const toml::node *n = node(key);
    return n ? colourFrom(*n, keyPath(key)) : std::nullopt;
}

std::optional<std::vector<Rgba>> TableReader::colours(std::string_view key)
{
    const toml::node *n = node(key);
    if (!n)
        return std::nullopt;
    const toml::array *array = n->as_array();
    if (!array) {
        problemAt(*n, keyPath(key), std::string("expected an array of colours, got ") + typeName(*n));
        return std::nullopt;
    }
    if (!withinCount(*array, keyPath(key), kMaxColours, "colours"))
        return std::nullopt;
    std::vector<Rgba> out;
    for (size_t i = 0; i < array->size(); ++i) {
        const auto c = colourFrom(*array->get(i), keyPath(key) + "[" + std::to_string(i) + "]");
        if (!c)
            return std::nullopt;
        out.push_back(*c);
    }
    return out;
}

std::optional<TableReader> TableReader::table(std::string_view key)
{
    const toml::node *n = node(key);
    if (!n)
        return std::nullopt;
    if (const toml::table *t = n->as_table())
        return TableReader(*t, keyPath(key), *problems_);
    problemAt(*n, keyPath(key), std::string("expected a table, got ") + typeName(*n));
    return std::nullopt;
}

std::vector<TableReader> TableReader::tables(std::string_view key, size_t maxCount, bool report)
{
    std::vector<TableReader> out;
    const toml::node *n = node(key);
    if (!n)
        return out;
    const toml::array *array = n->as_array();
    if (!array) {
        problemAt(*n, keyPath(key), std::string("expected [[") + std::string(key) + "]] tables, got " + typeName(*n));
        return out;
    }
    if (report)
        withinCount(*array, keyPath(key), maxCount, ("[[" + keyPath(key) + "]] tables").c_str());
    for (size_t i = 0; i < array->size() && i < maxCount; ++i) {
        const std::string path = keyPath(key) + "[" + std::to_string(i) + "]";
        if (const toml::table *t = array->get(i)->as_table())
            out.emplace_back(*t, path, *problems_);
        else
            problemAt(*array->get(i), path, std::string("expected a table, got ") + typeName(*array->get(i)));
    }
    return out;
}

} // namespace overlayd
