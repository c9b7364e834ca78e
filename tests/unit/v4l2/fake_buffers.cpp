// The fake V4L2 kernel: buffer requests, queueing and dequeueing, and frames produced by the test.
#include "fake_v4l2.h"

#include <algorithm>
#include <cerrno>

namespace overlayd::v4l2::test {

int FakeDevice::requestBuffers(v4l2_requestbuffers &r)
{
    if (r.type != bufferType || r.memory != V4L2_MEMORY_MMAP)
        return -EINVAL;
    if (streaming || mapped > 0)
        return -EBUSY;
    buffers.clear();
    queued.clear();
    done.clear();
    if (r.count == 0) {
        ++reqbufsZero;
        return 0;
    }
    r.count = std::clamp(r.count, 2u, 32u);
    buffers.resize(r.count);
    for (Buffer &b : buffers) {
        for (unsigned p = 0; p < memoryPlanes(); ++p)
            b.planes.emplace_back(planeLength(p), 0);
    }
    return 0;
}

int FakeDevice::queryBuffer(v4l2_buffer &b)
{
    if (b.type != bufferType || b.index >= buffers.size())
        return -EINVAL;
    if (!multiPlanar()) {
        b.length = planeLength(0);
        b.m.offset = fakeOffset(b.index, 0);
        return 0;
    }
    if (!b.m.planes || b.length < memoryPlanes())
        return -EINVAL;
    b.length = memoryPlanes();
    for (unsigned p = 0; p < memoryPlanes(); ++p) {
        b.m.planes[p].length = planeLength(p);
        b.m.planes[p].m.mem_offset = fakeOffset(b.index, p);
    }
    return 0;
}

int FakeDevice::queueBuffer(v4l2_buffer &b)
{
    ++qbufCalls;
    if (qbufError)
        return qbufError;
    if (b.type != bufferType || b.memory != V4L2_MEMORY_MMAP || b.index >= buffers.size() || buffers[b.index].queued)
        return -EINVAL;
    if (multiPlanar() && (!b.m.planes || b.length < memoryPlanes()))
        return -EINVAL;
    Buffer &buffer = buffers[b.index];
    buffer.queued = true;
    for (unsigned p = 0; p < memoryPlanes(); ++p)
        buffer.bytesUsed[p] = multiPlanar() ? b.m.planes[p].bytesused : b.bytesused;
    if (!output() || !consumeOutput) {
        queued.push_back(b.index);
        return 0;
    }
    std::vector<std::vector<uint8_t>> planes;
    for (unsigned p = 0; p < memoryPlanes(); ++p)
        planes.emplace_back(buffer.planes[p].begin(), buffer.planes[p].begin() + buffer.bytesUsed[p]);
    written.push_back(std::move(planes));
    done.push_back(b.index);
    return 0;
}

int FakeDevice::dequeueBuffer(v4l2_buffer &b)
{
    ++dqbufCalls;
    if (!dqbufErrors.empty()) {
        const int error = dqbufErrors.front();
        dqbufErrors.pop_front();
        return error;
    }
    if (b.type != bufferType || (multiPlanar() && (!b.m.planes || b.length < memoryPlanes())))
        return -EINVAL;
    if (!streaming)
        return -EINVAL;
    if (done.empty())
        return -EAGAIN;
    Buffer &buffer = buffers[done.front()];
    b.index = done.front();
    done.pop_front();
    buffer.queued = false;
    b.sequence = buffer.sequence;
    b.flags = buffer.flags;
    b.timestamp = buffer.timestamp;
    b.bytesused = buffer.bytesUsed[0];
    if (multiPlanar()) {
        b.length = memoryPlanes();
        for (unsigned p = 0; p < memoryPlanes(); ++p) {
            b.m.planes[p].bytesused = buffer.bytesUsed[p];
            b.m.planes[p].data_offset = dataOffset[p];
        }
    }
    return 0;
}

bool FakeDevice::produce(uint32_t sequence, std::chrono::microseconds timestamp,
                         const std::function<void(Buffer &)> &fill, uint32_t flags)
{
    if (queued.empty())
        return false;
    Buffer &buffer = buffers[queued.front()];
    for (unsigned p = 0; p < buffer.planes.size(); ++p)
        buffer.bytesUsed[p] = uint32_t(buffer.planes[p].size());
    if (fill)
        fill(buffer);
    buffer.sequence = sequence;
    buffer.flags = flags;
    buffer.timestamp = {long(timestamp.count() / 1000000), long(timestamp.count() % 1000000)};
    done.push_back(queued.front());
    queued.pop_front();
    return true;
}

} // namespace overlayd::v4l2::test
