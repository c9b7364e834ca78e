// SPDX-License-Identifier: Apache-2.0
// The libcamera entry points the driver factory and list-cameras call (libcamera_factory.cpp, or libcamera_none.cpp
// in builds without libcamera). No libcamera type crosses this header.
#pragma once

#include <memory>
#include <vector>

#include "base/result.h"
#include "drivers/camera_list.h"
#include "drivers/frame_source.h"
#include "drivers/source_options.h"

namespace overlayd {

Result<std::unique_ptr<FrameSource>> makeLibcameraSource(const SourceOptions &options);

} // namespace overlayd
