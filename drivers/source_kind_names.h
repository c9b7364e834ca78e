// SPDX-License-Identifier: Apache-2.0
// The source kinds' names, written once: `[source] kind` reads them, /state and the logs report them.
#pragma once

#include <span>
#include <string_view>
#include <utility>

#include "drivers/source_options.h"

namespace overlayd {

inline constexpr std::pair<std::string_view, SourceKind> kSourceKindNames[] = {
    {"synthetic", SourceKind::Synthetic},
    {"replay", SourceKind::Replay},
    {"v4l2", SourceKind::V4l2},
    {"libcamera", SourceKind::Libcamera},
};

inline std::string_view sourceKindName(SourceKind kind)
{
    for (const auto &[name, value] : kSourceKindNames)
        if (value == kind)
            return name;
    return "?";
}

} // namespace overlayd
