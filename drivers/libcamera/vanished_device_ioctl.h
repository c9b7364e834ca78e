// SPDX-License-Identifier: Apache-2.0
// The process's ioctl(): libcamera's VIDIOC_STREAMOFF and VIDIOC_QBUF on a V4L2 device that no longer exists report
// success, so that libcamera 0.3.2 can stop a camera whose device was unplugged.
#pragma once

#include <cstdint>
#include <string>

namespace overlayd {

// libcamera 0.3.2 cannot stop a camera whose device vanished under it (an unplugged or unbound device answers every
// ioctl with ENODEV, and only the uvcvideo pipeline tells libcamera of an unplug: vimc, rkisp1, ipu3, Raspberry Pi
// and simple never do), and stopping is the only way to end its IPA thread (destroying a camera whose IPA thread
// runs is std::terminate):
// - V4L2VideoDevice::streamOff() returns at the failed VIDIOC_STREAMOFF before it hands back the buffers queued in
//   the device; their requests never complete and PipelineHandler::stop() asserts (queuedRequests_ empty): abort;
// - V4L2VideoDevice::queueBuffer() keeps the buffer-cache slot of a failed VIDIOC_QBUF, so a later streamOff()
//   asserts (cache_->isEmpty()): abort.
// This file defines `ioctl` in the executable, which the dynamic linker binds every library's calls to. For calls
// made from libcamera.so only, a STREAMOFF or QBUF answered with ENODEV is reported done: the buffer stays queued
// in libcamera's books and the STREAMOFF hands it back cancelled, so the stop completes and the camera can be
// released and destroyed. Every other call and answer (overlayd's own V4L2 code included) is passed on unchanged.

// The seam: what the shim calls for every ioctl (by default the C library's, found with dlsym(RTLD_NEXT)).
using NextIoctl = int (*)(int fd, unsigned long request, void *arg);
// Tests only: replaces the next ioctl (nullptr: the C library's again).
void setNextIoctl(NextIoctl next);
// Tests only: the object (executable or library) holding `address` is the one whose calls are rewritten instead of
// libcamera.so (nullptr: libcamera.so again).
void setRewrittenCaller(const void *address);

// The file of the object whose calls are rewritten ("" when libcamera.so is not loaded).
std::string rewrittenCallerFile();
// How many STREAMOFFs and QBUFs the shim turned from ENODEV into success since the process started (any thread).
uint64_t vanishedDeviceCalls();

// Whether the dynamic linker binds `ioctl` to the shim (libcamera's calls then go through it).
bool vanishedDeviceIoctlInstalled();

} // namespace overlayd