// jsonString: a string as a JSON string literal, for the commands that print --json (names and ids come from
// drivers and may hold anything).
#pragma once

#include <string>

namespace overlayd {

std::string jsonString(const std::string &text);

} // namespace overlayd
