// DaemonStatus: the running daemon as the HTTP API reads it (/state, /metrics): read-only, no way back into the
// daemon. Daemon implements it; the API changes the scene only through SceneControl.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "config/daemon_config.h"
#include "control/can_inputs.h"
#include "control/gpio_control.h"
#include "control/path_inputs.h"
#include "control/run_state.h"
#include "control/text_inputs.h"
#include "inputs/input_health.h"
#include "media/stream.h"

namespace overlayd {

// One sink's counters as /state and /metrics show them.
struct SinkStatus {
    std::string name;
    uint64_t written = 0, dropped = 0, failed = 0;
};

class DaemonStatus
{
public:
    using State = RunState;

    virtual State state() const = 0;
    virtual const DaemonConfig &config() const = 0;
    // The stream the pipeline runs (no format: none yet) and the frames its source delivered.
    virtual const StreamFormat &streamFormat() const = 0;
    virtual uint64_t framesIn() const = 0;
    virtual std::vector<SinkStatus> sinkStatus() const = 0;
    virtual const GpioControl &gpio() const = 0;
    virtual const TextInputs &textInputs() const = 0;
    virtual const PathInputs &pathInputs() const = 0;
    virtual const CanInputs &canInputs() const = 0;
    // Every live input's health, whatever its kind: what /state and /metrics report of the inputs.
    virtual std::vector<inputs::InputHealth> inputHealth() const = 0;

protected:
    ~DaemonStatus() = default;
};

} // namespace overlayd
