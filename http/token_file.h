// SPDX-License-Identifier: Apache-2.0
// The control token's file, read by the server when it starts and by the config loader when it checks [http], so
// that check-config refuses every token file the server would.
#pragma once

#include <string>

#include "base/result.h"

namespace overlayd {

// The token: the first line of a readable regular file, trailing blanks and '\r' dropped, 1..kMaxTokenBytes
// (http_options.h) bytes. A FIFO or device is refused without being opened (reading one could block or never end).
// The error's message does not name the key: the caller says which.
Result<std::string> readTokenFile(const std::string &path);

} // namespace overlayd
