// SPDX-License-Identifier: Apache-2.0
// The ioctl() shim: libcamera's STREAMOFF and QBUF refused with ENODEV (the device is gone) are reported done.
#include "drivers/libcamera/vanished_device_ioctl.h"

#include <atomic>
#include <cerrno>
#include <cstdarg>

#include <dlfcn.h>
#include <sys/ioctl.h>

#include <linux/videodev2.h>

namespace overlayd {

namespace {

using LibcIoctl = int (*)(int, unsigned long, ...);

int libcIoctl(int fd, unsigned long request, void *arg)
{
    // Thread-safe once; dlsym calls no ioctl.
    static const auto next = reinterpret_cast<LibcIoctl>(::dlsym(RTLD_NEXT, "ioctl"));
    if (!next) {
        errno = ENOSYS;
        return -1;
    }
    return next(fd, request, arg);
}

// Where an object is loaded: what dladdr() says for any address inside it.
const void *objectBase(const void *address)
{
    Dl_info info{};
    return address && ::dladdr(address, &info) ? info.dli_fbase : nullptr;
}

const void *libcameraBase()
{
    // CameraManager::start(), exported by every libcamera 0.x (the base is looked up when first needed: libcamera.so
    // is linked, so it is loaded before any of its calls).
    return objectBase(::dlsym(RTLD_DEFAULT, "_ZN9libcamera13CameraManager5startEv"));
}

std::atomic<NextIoctl> nextIoctl{&libcIoctl};
std::atomic<const void *> rewrittenBase{nullptr};
std::atomic<bool> rewrittenSet{false};
std::atomic<uint64_t> vanished{0};

const void *rewritten()
{
    if (!rewrittenSet.load()) {
        rewrittenBase = libcameraBase();
        rewrittenSet = true;
    }
    return rewrittenBase.load();
}

bool fromRewrittenCaller(const void *returnAddress)
{
    const void *base = rewritten();
    return base && objectBase(returnAddress) == base;
}

// Called from ioctl() only on an ENODEV answer, so the dladdr() lookup costs nothing on the frame path.
bool rewriteVanished(unsigned long request, const void *returnAddress)
{
    if (request != VIDIOC_STREAMOFF && request != VIDIOC_QBUF)
        return false;
    if (!fromRewrittenCaller(returnAddress))
        return false;
    vanished.fetch_add(1);
    return true;
}

} // namespace

void setNextIoctl(NextIoctl next)
{
    nextIoctl = next ? next : &libcIoctl;
}

void setRewrittenCaller(const void *address)
{
    rewrittenBase = address ? objectBase(address) : libcameraBase();
    rewrittenSet = true;
}

std::string rewrittenCallerFile()
{
    Dl_info info{};
    const void *base = rewritten();
    return base && ::dladdr(base, &info) && info.dli_fname ? info.dli_fname : "";
}

uint64_t vanishedDeviceCalls()
{
    return vanished.load();
}

bool vanishedDeviceIoctlInstalled()
{
    return ::dlsym(RTLD_DEFAULT, "ioctl") == reinterpret_cast<void *>(&::ioctl);
}

} // namespace overlayd
// Defined in the executable, so it comes first in the global lookup scope: libcamera.so's (and every library's)
// calls to ioctl reach it. The C library reads the third argument as a pointer in the same way.
extern "C" int ioctl(int fd, unsigned long request, ...) noexcept
{
    va_list args;
    va_start(args, request);
    void *arg = va_arg(args, void *);
    va_end(args);
    const int saved = errno;
    const int result = overlayd::nextIoctl.load()(fd, request, arg);
    if (result < 0 && errno == ENODEV && overlayd::rewriteVanished(request, __builtin_return_address(0))) {
        errno = saved;
        return 0;
    }
    return result;
}
