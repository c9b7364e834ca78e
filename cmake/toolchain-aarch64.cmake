# SPDX-License-Identifier: Apache-2.0
# Cross build for arm64 (aarch64) with Debian 12's crossbuild-essential-arm64 against the sysroot that
# scripts/arm64/sysroot.sh unpacks from Debian's own arm64 packages. CTest runs the built programs under
# qemu-aarch64 in that sysroot (CMAKE_CROSSCOMPILING_EMULATOR), so `ctest` works as it does natively.
#   cmake -S . -B build-arm64 -DCMAKE_TOOLCHAIN_FILE=cmake/toolchain-aarch64.cmake -DOVERLAYD_ARM64_SYSROOT=...
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64) # the SIMD dispatch keys off it: NEON, no x86 paths

# try_compile's inner projects read this file again: hand them the sysroot chosen here.
list(APPEND CMAKE_TRY_COMPILE_PLATFORM_VARIABLES OVERLAYD_ARM64_SYSROOT)
if(NOT OVERLAYD_ARM64_SYSROOT)
    set(OVERLAYD_ARM64_SYSROOT "${CMAKE_CURRENT_LIST_DIR}/../.cache/arm64/sysroot")
endif()
get_filename_component(OVERLAYD_ARM64_SYSROOT "${OVERLAYD_ARM64_SYSROOT}" ABSOLUTE)
set(OVERLAYD_ARM64_SYSROOT "${OVERLAYD_ARM64_SYSROOT}" CACHE PATH "The arm64 sysroot (scripts/arm64/sysroot.sh)")
if(NOT EXISTS "${OVERLAYD_ARM64_SYSROOT}/.overlayd-sysroot")
    message(FATAL_ERROR "No arm64 sysroot at ${OVERLAYD_ARM64_SYSROOT}: run scripts/arm64/sysroot.sh first")
endif()

set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
set(CMAKE_SYSROOT "${OVERLAYD_ARM64_SYSROOT}")
set(CMAKE_FIND_ROOT_PATH "${OVERLAYD_ARM64_SYSROOT}")
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
set(CMAKE_LIBRARY_ARCHITECTURE aarch64-linux-gnu)

# pkg-config reads the sysroot's .pc files and prefixes their paths with it.
set(ENV{PKG_CONFIG_SYSROOT_DIR} "${OVERLAYD_ARM64_SYSROOT}")
set(ENV{PKG_CONFIG_LIBDIR}
    "${OVERLAYD_ARM64_SYSROOT}/usr/lib/aarch64-linux-gnu/pkgconfig:${OVERLAYD_ARM64_SYSROOT}/usr/share/pkgconfig")
set(ENV{PKG_CONFIG_PATH} "")

# The libraries' own dependencies are resolved inside the sysroot at link time.
string(APPEND CMAKE_EXE_LINKER_FLAGS_INIT
       " -Wl,-rpath-link,${OVERLAYD_ARM64_SYSROOT}/usr/lib/aarch64-linux-gnu")
string(APPEND CMAKE_SHARED_LINKER_FLAGS_INIT
       " -Wl,-rpath-link,${OVERLAYD_ARM64_SYSROOT}/usr/lib/aarch64-linux-gnu")

set(CMAKE_CROSSCOMPILING_EMULATOR qemu-aarch64 -L "${OVERLAYD_ARM64_SYSROOT}")
