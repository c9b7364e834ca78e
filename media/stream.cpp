// Human-readable stream descriptions.
#include "media/stream.h"

#include <cstdio>

namespace overlayd {

std::string StreamFormat::describe() const
{
    char text[96];
    std::snprintf(text, sizeof(text), "%ux%u %s %.1f fps", width, height,
                  format ? std::string(format->name).c_str() : "?", fps);
    return text;
}

} // namespace overlayd
