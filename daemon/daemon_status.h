// DaemonStatus: the running daemon as the HTTP API reads it (/state, /metrics): read-only, no way back into the
// daemon. Daemon implements it; the API changes the scene only through SceneControl.
#pragma once

#include <vector>

#include "config/daemon_config.h"
#include "daemon/can_inputs.h"
#include "daemon/gpio_control.h"
#include "daemon/path_inputs.h"
#include "daemon/pipeline.h"
#include "daemon/source_supervisor.h"
#include "daemon/text_inputs.h"
#include "inputs/input_health.h"
#include "stream/encoded_stream.h"

namespace overlayd {

class DaemonStatus
{
public:
    using State = SourceSupervisor::State;

    virtual State state() const = 0;
    virtual const DaemonConfig &config() const = 0;
    virtual const Pipeline &pipeline() const = 0;
    virtual const GpioControl &gpio() const = 0;
    virtual const TextInputs &textInputs() const = 0;
    virtual const PathInputs &pathInputs() const = 0;
    virtual const CanInputs &canInputs() const = 0;
    // Every live input's health, whatever its kind: what /state and /metrics report of the inputs.
    virtual std::vector<inputs::InputHealth> inputHealth() const = 0;
    // The encoded outputs' encoder and sinks; null when no encoded sink is configured.
    virtual const stream::EncodedStream *encodedStream() const = 0;

protected:
    ~DaemonStatus() = default;
};

} // namespace overlayd
