// SPDX-License-Identifier: Apache-2.0
// The file name extension of each container.
#include "stream/record_options.h"

namespace overlayd {

std::string_view containerExtension(RecordContainer container)
{
    return container == RecordContainer::Mp4 ? "mp4" : "mkv";
}

} // namespace overlayd
