// SPDX-License-Identifier: Apache-2.0
// DaemonStatus: the running daemon as the HTTP API reads it (/state, /metrics): read-only, no way back into the
// daemon. Daemon implements it; the API changes the scene only through SceneControl.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "config/daemon_config.h"
#include "control/run_state.h"
#include "control/status_reporter.h"
#include "media/stream.h"
#include "stream/encoded_stream.h"

namespace overlayd {

class DaemonStatus
{
public:
    using State = RunState;

    virtual State state() const = 0;
    virtual const DaemonConfig &config() const = 0;
    // The stream the pipeline runs (no format: none yet) and the frames its source delivered.
    virtual const StreamFormat &streamFormat() const = 0;
    virtual uint64_t framesIn() const = 0;
    // Every part that reports itself in /state and /metrics (the sinks, GPIO, each kind of input), in the order
    // their entries appear.
    virtual std::vector<const StatusReporter *> reporters() const = 0;
    // The encoded stream running now (null: none), which WHEP's peers join.
    virtual std::shared_ptr<EncodedStream> encodedStream() const { return nullptr; }

protected:
    ~DaemonStatus() = default;
};

} // namespace overlayd
