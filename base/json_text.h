// SPDX-License-Identifier: Apache-2.0
// JSON text for the commands that print --json: strings (names and ids come from drivers and may hold anything)
// and numbers.
#pragma once

#include <string>

namespace overlayd {

std::string jsonString(const std::string &text);
// The shortest text that reads back as the same double (std::to_chars); "null" when not finite.
std::string jsonNumber(double value);

} // namespace overlayd
