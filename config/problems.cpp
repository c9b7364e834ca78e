// SPDX-License-Identifier: Apache-2.0
// Problems and "did you mean": collecting config errors and suggesting the key a typo meant.
#include "config/problems.h"

#include <algorithm>

namespace overlayd {

std::string ConfigProblem::format() const
{
    std::string out = file + ":" + std::to_string(line) + ":" + std::to_string(column) + ": ";
    if (!key.empty())
        out += key + ": ";
    return out + message;
}

void Problems::add(unsigned line, unsigned column, std::string key, std::string message, std::string file)
{
    if (list_.size() >= kMaxListedProblems) {
        ++unlisted_;
        return;
    }
    list_.push_back(
        ConfigProblem{file.empty() ? file_ : std::move(file), line, column, std::move(key), std::move(message)});
}

std::vector<ConfigProblem> Problems::sorted() const
{
    std::vector<ConfigProblem> out = list_;
    std::stable_sort(out.begin(), out.end(), [](const ConfigProblem &a, const ConfigProblem &b) {
        return a.line != b.line ? a.line < b.line : a.column < b.column;
    });
    if (unlisted_ > 0)
        out.push_back(ConfigProblem{file_, 0, 0, "", std::to_string(unlisted_) + " more problem(s) not listed"});
    return out;
}

std::string shown(std::string_view name)
{
    if (name.size() <= kMaxShownBytes)
        return std::string(name);
    return std::string(name.substr(0, kMaxShownBytes)) + "...(" + std::to_string(name.size()) + " bytes)";
}

// Optimal string alignment distance: Levenshtein plus adjacent transpositions ("widht" is one edit from
// "width"), the commonest typo in a key.
size_t editDistance(std::string_view a, std::string_view b)
{
    std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
    for (size_t i = 0; i <= a.size(); ++i)
        d[i][0] = i;
    for (size_t j = 0; j <= b.size(); ++j)
        d[0][j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
        for (size_t j = 1; j <= b.size(); ++j) {
            const size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
            d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
                d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
        }
    }
    return d[a.size()][b.size()];
}

std::string closestMatch(std::string_view word, const std::vector<std::string> &candidates)
{
    if (word.size() > kMaxSuggestedBytes)
        return {};
    // About a third of the word's letters (1 to 3 edits) may be wrong; beyond that a suggestion misleads.
    const size_t allowed = std::clamp<size_t>((word.size() + 1) / 3, 1, 3);
    std::string best;
    size_t bestDistance = SIZE_MAX;
    for (size_t i = 0; i < candidates.size() && i < kMaxSuggestionCandidates; ++i) {
        const std::string &candidate = candidates[i];
        // Lengths further apart than `allowed` are that many edits apart at least: not worth comparing.
        if (candidate.size() > word.size() + allowed || word.size() > candidate.size() + allowed)
            continue;
        const size_t distance = editDistance(word, candidate);
        if (distance < bestDistance) {
            bestDistance = distance;
            best = candidate;
        }
    }
    return bestDistance <= allowed ? best : std::string();
}

} // namespace overlayd
