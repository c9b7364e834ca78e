// SPDX-License-Identifier: Apache-2.0
// Config controls against libcamera: by name and type through its registry (no camera needed), by range against an
// opened camera's ControlInfoMap.
#pragma once

#include <string>
#include <vector>

#include <libcamera/controls.h>

#include "base/result.h"
#include "drivers/source_options.h"

namespace overlayd {

// The ControlList that start() hands to Camera::start(). Every problem is reported, each in the config's shape
// ("file:line:column: source.libcamera.controls.Brightness: 2 is outside -1..1"), one per line.
Result<libcamera::ControlList> buildControls(const std::vector<ControlSetting> &settings,
                                             const libcamera::ControlInfoMap &camera);

} // namespace overlayd
