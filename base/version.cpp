// SPDX-License-Identifier: Apache-2.0
// Only this file sees the generated header, so a new commit recompiles one file.
#include "base/version.h"

#include "overlayd_version.h"

namespace overlayd {

const char *overlaydVersion()
{
    return OVERLAYD_VERSION;
}

} // namespace overlayd
