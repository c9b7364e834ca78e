// SPDX-License-Identifier: Apache-2.0
// The fake V4L2 kernel: buffer requests, queueing and dequeueing, and frames produced by the test.
#include "fake_v4l2.h"

#include <algorithm>
#include <cerrno>

namespace overlayd::test {

int FakeDevice::requestBuffers(v4l2_requestbuffers &r)
{
    const bool dmabuf = r.memory == V4L2_MEMORY_DMABUF && importsDmabuf;
    if (r.type != bufferType || (r.memory != V4L2_MEMORY_MMAP && !dmabuf))
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
    memory = r.memory;
    for (Buffer &b : buffers) {
        if (dmabuf)
            break; // the memory is the application's dmabufs
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
    if (b.type != bufferType || b.memory != memory || b.index >= buffers.size() || buffers[b.index].queued)
        return -EINVAL;
    if (multiPlanar() && (!b.m.planes || b.length < memoryPlanes()))
        return -EINVAL;
    Buffer &buffer = buffers[b.index];
    for (unsigned p = 0; p < memoryPlanes(); ++p)
        buffer.bytesUsed[p] = multiPlanar() ? b.m.planes[p].bytesused : b.bytesused;
    if (memory == V4L2_MEMORY_DMABUF) {
        if (const int r = importDmabufs(buffer, b); r < 0)
            return r;
    }
    buffer.queued = true;
    queued.push_back(b.index);
    if (output() && consumeOutput)
        consume();
    return 0;
}

// As vb2 checks a DMABUF QBUF: a live dmabuf per plane, length at least the format's plane size and at least
// bytesused, data_offset inside bytesused; the single-planar API has no data_offset.
int FakeDevice::importDmabufs(Buffer &buffer, const v4l2_buffer &b)
{
    for (unsigned p = 0; p < memoryPlanes(); ++p) {
        const int fd = multiPlanar() ? b.m.planes[p].m.fd : b.m.fd;
        const uint32_t length = multiPlanar() ? b.m.planes[p].length : b.length;
        const uint32_t offset = multiPlanar() ? b.m.planes[p].data_offset : 0;
        const std::vector<uint8_t> *bytes = dmabufBytes ? dmabufBytes(fd) : nullptr;
        if (!bytes || length > bytes->size() || length < planeLength(p) || buffer.bytesUsed[p] > length ||
            (offset > 0 && offset >= buffer.bytesUsed[p]))
            return -EINVAL;
        buffer.dmabufFds[p] = fd;
        buffer.dataOffset[p] = offset;
    }
    return 0;
}

bool FakeDevice::consume()
{
    if (queued.empty())
        return false;
    record(buffers[queued.front()]);
    done.push_back(queued.front());
    queued.pop_front();
    return true;
}

// What the device reads of a buffer: from data_offset to bytesused of each plane, its own memory or the dmabuf's.
void FakeDevice::record(const Buffer &buffer)
{
    std::vector<std::vector<uint8_t>> planes;
    for (unsigned p = 0; p < memoryPlanes(); ++p) {
        const std::vector<uint8_t> *bytes =
            memory == V4L2_MEMORY_DMABUF ? dmabufBytes(buffer.dmabufFds[p]) : &buffer.planes[p];
        if (!bytes || buffer.bytesUsed[p] > bytes->size()) {
            planes.emplace_back(); // the dmabuf went away under the device
            continue;
        }
        planes.emplace_back(bytes->begin() + buffer.dataOffset[p], bytes->begin() + buffer.bytesUsed[p]);
    }
    written.push_back(std::move(planes));
}

int FakeDevice::dequeueBuffer(v4l2_buffer &b)
{
    ++dqbufCalls;
    if (!dqbufErrors.empty()) {
        const int error = dqbufErrors.front();
        dqbufErrors.pop_front();
        return error;
    }
    if (b.type != bufferType || b.memory != memory || (multiPlanar() && (!b.m.planes || b.length < memoryPlanes())))
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

} // namespace overlayd::test
