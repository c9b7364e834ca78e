// SPDX-License-Identifier: Apache-2.0
// Blocks the stop signals from DT_PREINIT_ARRAY: the dynamic loader runs it right after relocation, before the
// constructors of every shared library (liblttng-ust's, through libcamera, reads each loaded object for ~100 ms and
// starts threads). What comes earlier — the kernel's exec and the loader itself — no program can cover; see
// docs/daemon.md, "Signals".
#include "tools/early_signals.h"

#include <csignal>
#include <initializer_list>

#include <pthread.h>

namespace overlayd {

namespace {

sigset_t inheritedMask;

void blockStopSignals(int, char **, char **)
{
    sigset_t stop;
    sigemptyset(&stop);
    for (int signal : {SIGTERM, SIGINT, SIGHUP})
        sigaddset(&stop, signal);
    pthread_sigmask(SIG_BLOCK, &stop, &inheritedMask);
}

// Only an executable's preinit array is run; this file is linked into `overlayd` itself for that reason.
[[gnu::section(".preinit_array"), gnu::used]] void (*const preinitBlockStopSignals)(int, char **,
                                                                                    char **) = blockStopSignals;

} // namespace

void restoreInheritedSignalMask()
{
    pthread_sigmask(SIG_SETMASK, &inheritedMask, nullptr);
}

} // namespace overlayd
