// SPDX-License-Identifier: Apache-2.0
// The stop signals from the executable's first instruction: SIGTERM, SIGINT and SIGHUP are blocked before any
// library constructor runs, so that a signal sent while overlayd starts is kept pending for `run`'s signalfd
// instead of ending the process with the default action.
#pragma once

namespace overlayd {

// The other commands are ordinary tools: a stop signal ends them as usual. Gives back the mask the process was
// started with (a pending SIGTERM then acts at once).
void restoreInheritedSignalMask();

} // namespace overlayd
