// SPDX-License-Identifier: Apache-2.0
// RunState: where the daemon's stream stands, as the control adapters see it (GPIO outputs follow it, /state and
// /metrics report it). The source supervisor in daemon/ keeps it; it lives here so that control/ needs no daemon/.
#pragma once

namespace overlayd {

enum class RunState { Idle, Streaming, Waiting, Finished };

} // namespace overlayd
