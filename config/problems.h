// SPDX-License-Identifier: Apache-2.0
// Problems: collects every ConfigProblem of one load, so that a user sees them all in one pass.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "config/daemon_config.h"

namespace overlayd {

// The most problems one load lists: 10000 unknown keys still make a short answer (the rest are counted).
inline constexpr size_t kMaxListedProblems = 100;

class Problems
{
public:
    explicit Problems(std::string file) : file_(std::move(file)) {}

    // `file` names another file than the one loaded (a drop-in read with it); empty: the loaded one.
    void add(unsigned line, unsigned column, std::string key, std::string message, std::string file = {});
    bool empty() const { return size() == 0; }
    size_t size() const { return list_.size() + unlisted_; } // every problem found, listed or not
    const std::string &file() const { return file_; }
    // In file order (line, then column), the order a user fixes them in; the first kMaxListedProblems found, then
    // one line counting the rest.
    std::vector<ConfigProblem> sorted() const;

private:
    std::string file_;
    std::vector<ConfigProblem> list_;
    size_t unlisted_ = 0;
};

// A name from the file as a message quotes it: at most kMaxShownBytes, then how long it was.
inline constexpr size_t kMaxShownBytes = 64;
std::string shown(std::string_view name);

// Levenshtein distance, for "did you mean".
size_t editDistance(std::string_view a, std::string_view b);
// Suggestion work is bounded: a word longer than kMaxSuggestedBytes gets no suggestion, and only the first
// kMaxSuggestionCandidates candidates are compared (a word of 100 KB or 10000 unknown keys cost little each).
inline constexpr size_t kMaxSuggestedBytes = 64;
inline constexpr size_t kMaxSuggestionCandidates = 256;
// The candidate closest to `word` when it is close enough to be a plausible typo, else empty.
std::string closestMatch(std::string_view word, const std::vector<std::string> &candidates);

} // namespace overlayd
