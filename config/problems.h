// Problems: collects every ConfigProblem of one load, so that a user sees them all in one pass.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "config/daemon_config.h"

namespace overlayd::config {

class Problems
{
public:
    explicit Problems(std::string file) : file_(std::move(file)) {}

    // `file` names another file than the one loaded (a drop-in read with it); empty: the loaded one.
    void add(unsigned line, unsigned column, std::string key, std::string message, std::string file = {});
    bool empty() const { return list_.empty(); }
    size_t size() const { return list_.size(); }
    const std::string &file() const { return file_; }
    // In file order (line, then column), the order a user fixes them in.
    std::vector<ConfigProblem> sorted() const;

private:
    std::string file_;
    std::vector<ConfigProblem> list_;
};

// Levenshtein distance, for "did you mean".
size_t editDistance(std::string_view a, std::string_view b);
// The candidate closest to `word` when it is close enough to be a plausible typo, else empty.
std::string closestMatch(std::string_view word, const std::vector<std::string> &candidates);

} // namespace overlayd::config
