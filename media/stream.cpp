// SPDX-License-Identifier: Apache-2.0
// Human-readable stream descriptions.
#include "media/stream.h"

#include "base/number_text.h"

#include <cstdio>

namespace overlayd {

std::string StreamFormat::describe() const
{
    return formatted("%ux%u %s %.1f fps", width, height, format ? std::string(format->name).c_str() : "?", fps);
}

} // namespace overlayd
