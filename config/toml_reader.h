// SPDX-License-Identifier: Apache-2.0
// TableReader: typed, located access to one TOML table; every wrong type, bad value and unknown key becomes a
// Problem with its file:line:column instead of stopping the load. Private to config/ (toml++ stays inside).
#pragma once

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <toml++/toml.h>

#include "base/number_range.h"
#include "config/problems.h"
#include "media/rgba.h"

namespace overlayd {

// The longest string without a narrower limit (paths: Linux's PATH_MAX).
inline constexpr size_t kMaxStringBytes = 4096;
// The control characters a config string may hold (a multi-line text); any other is refused.
inline constexpr std::string_view kConfigStringControls = "\t\n\r";

class TableReader
{
public:
    TableReader(const toml::table &table, std::string path, Problems &problems);

    // Marks the key as known whether or not it is present (see finish()).
    const toml::node *node(std::string_view key);
    bool has(std::string_view key) { return node(key) != nullptr; }
    std::string keyPath(std::string_view key) const;
    const std::string &path() const { return path_; }
    Problems &problems() { return *problems_; }

    // A problem at the key (its value's position), or at the table when the key is absent.
    void problem(std::string_view key, std::string message);
    void problemAtTable(std::string message);
    // At a dotted key path below this table ("style.dash"), or at the deepest table of it that exists.
    void problemAtPath(std::string_view dottedKey, std::string message);
    void problemAt(const toml::node &at, const std::string &keyPath, std::string message);

    // Each returns nullopt when the key is absent, or (after recording a problem) when it is invalid.
    // Numbers accept integers and floats and must lie within their range (which also keeps out inf and nan);
    // vectors, lists and points check each entry against it.
    std::optional<double> number(std::string_view key, double min = -kMaxMagnitude, double max = kMaxMagnitude);
    // As number(), but > 0 (an open lower bound: sizes, fps, focal lengths).
    std::optional<double> positive(std::string_view key, double max = kMaxMagnitude);
    std::optional<int64_t> integer(std::string_view key, int64_t min, int64_t max);
    std::optional<bool> boolean(std::string_view key);
    // At most maxBytes long.
    std::optional<std::string> string(std::string_view key, size_t maxBytes = kMaxStringBytes);
    template<typename E>
    std::optional<E> choice(std::string_view key, std::initializer_list<std::pair<std::string_view, E>> names)
    {
        return choice(key, std::span<const std::pair<std::string_view, E>>(names.begin(), names.size()));
    }
    // The same from a table of names written elsewhere (drivers/source_kind_names.h).
    template<typename E>
    std::optional<E> choice(std::string_view key, std::span<const std::pair<std::string_view, E>> names);
    std::optional<glm::dvec2> vec2(std::string_view key, Range range = {}) { return vector<glm::dvec2, 2>(key, range); }
    std::optional<glm::dvec3> vec3(std::string_view key, Range range = {}) { return vector<glm::dvec3, 3>(key, range); }
    // [w, x, y, z], normalized; a zero quaternion is refused.
    std::optional<glm::dquat> quaternion(std::string_view key);
    // At most maxCount numbers (or points); the first one over is refused at its own position.
    std::optional<std::vector<double>> numbers(std::string_view key, size_t maxCount, Range range = {});
    std::optional<std::vector<glm::dvec3>> points(std::string_view key, size_t maxCount, Range range = {});
    // The same, also taking [x, y] points (z = 0) when `screen` is given: *screen says which, all alike.
    std::optional<std::vector<glm::dvec3>> points(std::string_view key, size_t maxCount, Range range, bool *screen);
    // An array of at most maxCount strings.
    std::optional<std::vector<std::string>> strings(std::string_view key, size_t maxCount);
    // "#rrggbb", "#rrggbbaa", a colour name, or [r, g, b] / [r, g, b, a] with 0..255 entries.
    std::optional<Rgba> colour(std::string_view key);
    std::optional<std::vector<Rgba>> colours(std::string_view key);
    std::optional<TableReader> table(std::string_view key);
    // [[key]] arrays of tables: the first maxCount; one more is refused at its own [[key]] (when `report`: a
    // section read twice reports once).
    std::vector<TableReader> tables(std::string_view key, size_t maxCount, bool report = true);
    // An array's entries beyond maxCount are refused at the first one over: false then.
    bool withinCount(const toml::array &array, const std::string &path, size_t maxCount, const char *what);

    // Reports every key of the table that no reader asked about, suggesting the nearest known key.
    void finish();
    // Marks every key present as known, when their meaning cannot be judged (an unknown annotation type).
    void ignoreRest();

private:
    template<typename V, int N>
    std::optional<V> vector(std::string_view key, Range range);
    std::optional<double> numberFrom(const toml::node &node, const std::string &path, Range range);
    std::optional<Rgba> colourFrom(const toml::node &node, const std::string &path);
    std::optional<std::string> unmatchedChoice(std::string_view key, const std::vector<std::string> &names);

    const toml::table *table_;
    std::string path_;
    Problems *problems_;
    std::vector<std::string> known_;
};

const char *typeName(const toml::node &node);

template<typename V, int N>
std::optional<V> TableReader::vector(std::string_view key, Range range)
{
    const toml::node *n = node(key);
    if (!n)
        return std::nullopt;
    const toml::array *array = n->as_array();
    if (!array || array->size() != size_t(N)) {
        problemAt(*n, keyPath(key), "expected an array of " + std::to_string(N) + " numbers, got " + typeName(*n));
        return std::nullopt;
    }
    V out(0.0);
    for (int i = 0; i < N; ++i) {
        const auto value = numberFrom(*array->get(size_t(i)), keyPath(key) + "[" + std::to_string(i) + "]", range);
        if (!value)
            return std::nullopt;
        out[i] = *value;
    }
    return out;
}

template<typename E>
std::optional<E> TableReader::choice(std::string_view key, std::span<const std::pair<std::string_view, E>> names)
{
    const std::optional<std::string> text = string(key);
    if (!text)
        return std::nullopt;
    std::vector<std::string> all;
    for (const auto &[name, value] : names) {
        if (name == *text)
            return value;
        all.emplace_back(name);
    }
    unmatchedChoice(key, all);
    return std::nullopt;
}

} // namespace overlayd
