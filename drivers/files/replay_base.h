// SPDX-License-Identifier: Apache-2.0
// What the replay sources share: the frame pool, numbering, timestamps at the stream's fps, and looping.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "drivers/source_options.h"
#include "media/frame_pool.h"

namespace overlayd {

class ReplaySource : public FrameSource
{
public:
    explicit ReplaySource(const SourceOptions &options) : options_(options) {}

    Result<StreamFormat> start() override;
    void stop() override;
    int eventFd() const override { return -1; }
    // A Malformed or Io error is sticky: the stream is broken, every later call answers the same.
    Result<FrameLease> nextFrame() override;
    std::string describe() const override;

protected:
    // Opens the file (or first image) and says what frames it holds.
    virtual Result<StreamFormat> open() = 0;
    virtual void close() = 0;
    // Reads the frame `index` of the file (counting from 0) into the buffer; EndOfStream exactly at the end.
    virtual Status read(uint64_t index, FrameBuffer &buffer) = 0;
    // Back to the first frame for the next read (loop).
    virtual Status rewind() = 0;
    virtual const char *kind() const = 0;

    // "in.y4m: frame 3: ..." for Malformed errors.
    Error malformed(uint64_t index, const std::string &why) const;

    SourceOptions options_;
    StreamFormat format_{};

private:
    Status readLooping(FrameBuffer &buffer);

    std::shared_ptr<FramePool> pool_;
    uint64_t sequence_ = 0;  // frames delivered since start()
    uint64_t fileIndex_ = 0; // the next frame's index in the file
    std::optional<Error> failure_;
    std::chrono::system_clock::time_point startWall_{};
};

// Each checks its own options and opens nothing.
Result<std::unique_ptr<FrameSource>> makeY4mSource(const SourceOptions &options);
Result<std::unique_ptr<FrameSource>> makeRawSource(const SourceOptions &options);
Result<std::unique_ptr<FrameSource>> makeImageSource(const SourceOptions &options);

} // namespace overlayd
