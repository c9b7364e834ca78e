// SPDX-License-Identifier: Apache-2.0
// The one version of overlayd: `overlayd --version`, /state's "version" and the Debian package's name.
#pragma once

namespace overlayd {

// From the git tags at build time (cmake/overlayd_version.cmake), else the VERSION file: "0.2.0", "0.2.0+5.gabc1234".
const char *overlaydVersion();

} // namespace overlayd
