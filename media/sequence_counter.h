// SPDX-License-Identifier: Apache-2.0
// SequenceCounter: a driver's 32-bit frame sequence numbers as the stream's own count from 0, and the frames lost in
// the gaps between them (V4L2 buffers and libcamera requests number frames the same way).
#pragma once

#include <cstdint>

namespace overlayd {

class SequenceCounter
{
public:
    // The next frame starts the count again (a new start()).
    void restart() { started_ = false; }
    // Takes the driver's number of the next frame; answers how many frames were lost just before it. Unsigned
    // differences survive the driver's counter wrapping; a number that goes backwards counts as no loss.
    uint32_t advance(uint32_t sequence)
    {
        if (!started_)
            first_ = next_ = sequence;
        started_ = true;
        const uint32_t gap = sequence - next_;
        next_ = sequence + 1;
        return gap < (1u << 31) ? gap : 0;
    }
    // The frame's number counted from the first frame since restart().
    uint32_t relative(uint32_t sequence) const { return sequence - first_; }

private:
    bool started_ = false;
    uint32_t first_ = 0, next_ = 0;
};

} // namespace overlayd
