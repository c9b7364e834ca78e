// SPDX-License-Identifier: Apache-2.0
// EncodedStreamReport: the encoded outputs as /state and /metrics show them: the encoder (kind, device, measured
// bitrate, keyframes, frames dropped before it), each encoded sink with its clients (address, transport, since), and
// the latency of every stage from capture.
#pragma once

#include <memory>

#include "control/status_reporter.h"
#include "stream/encoded_stream.h"

namespace overlayd {

class EncodedStreamReport final : public StatusReporter
{
public:
    // Reads whichever stream `running` holds when asked (the daemon swaps it on a reload); none: reports nothing.
    explicit EncodedStreamReport(const std::shared_ptr<EncodedStream> &running) : running_(running) {}

    void report(StatusReport &report) const override;

private:
    const std::shared_ptr<EncodedStream> &running_;
};

} // namespace overlayd
