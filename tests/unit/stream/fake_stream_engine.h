// SPDX-License-Identifier: Apache-2.0
// FakeStreamEngine: an EncodedStreamEngine that keeps what it is pushed, for the daemon's side's tests. Frames stay
// held (as GStreamer would hold them in its queues) until the test releases them.
#pragma once

#include <vector>

#include "stream/encoded_stream_engine.h"

namespace overlayd::test {

class FakeStreamEngine : public EncodedStreamEngine
{
public:
    struct Calls {
        unsigned opens = 0, closes = 0;
        EngineFormat format;
        std::vector<EncoderInput> held; // pushed and not yet released
        uint64_t pushed = 0;
        bool importsDmabuf = false; // as a V4L2 encoder: takes DMABUF frames when opened for them
    };
    explicit FakeStreamEngine(Calls &calls) : calls_(calls) {}

    Status open(const EngineFormat &format) override
    {
        ++calls_.opens;
        calls_.format = format;
        return Ok{};
    }
    void push(EncoderInput frame) override
    {
        ++calls_.pushed;
        calls_.held.push_back(std::move(frame));
    }
    void close() override
    {
        ++calls_.closes;
        calls_.held.clear(); // as a pipeline set to NULL drops every buffer
    }
    EngineState state() const override
    {
        EngineState state;
        state.encoder = "fake";
        state.framesIn = calls_.pushed;
        state.dmabufImport = calls_.importsDmabuf && calls_.format.dmabuf;
        return state;
    }

private:
    Calls &calls_;
};

} // namespace overlayd::test
