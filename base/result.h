// SPDX-License-Identifier: Apache-2.0
// Result<T>: a value or an Error, returned instead of throwing where bad input is expected.
#pragma once

#include <string>
#include <utility>
#include <variant>

namespace overlayd {

enum class ErrorCode {
    InvalidArgument, // a value out of its documented range (near <= 0, fov >= 180, ...)
    DegenerateBasis, // vectors that cannot span a camera frame (zero, or up parallel to gaze)
    NotOrthonormal,  // a rotation matrix that is not a rotation
    UnknownFrame,    // a scene-graph frame name that does not exist
    DuplicateFrame,  // a scene-graph frame name given twice
    CyclicFrames,    // scene-graph parents that form a loop
    Unsupported,     // a combination the model does not define (e.g. distortion without pinhole intrinsics)
    NoConvergence,   // an iterative inversion (undistortion) that did not converge
    // Sources, sinks and files (the frame path returns these instead of throwing).
    NotFound,    // a file or device that does not exist
    Io,          // a read or write that failed (errno in the message)
    Malformed,   // a file whose contents do not parse (names the file and, where it applies, the frame)
    EndOfStream, // a finite source has no more frames
    TryAgain,    // nothing ready yet (EAGAIN); not a failure
    DeviceLost,  // the device vanished or stopped answering (ENODEV, EIO, timeout); retry later
    ConfigError, // a config file that does not validate (the message lists every problem)
};

const char *errorCodeName(ErrorCode code);

struct Error {
    ErrorCode code;
    std::string message;
};

// A small stand-in for C++23 std::expected: either a T or an Error.
template<typename T>
class [[nodiscard]] Result
{
public:
    Result(T value) : state_(std::move(value)) {}
    Result(Error error) : state_(std::move(error)) {}

    bool ok() const { return std::holds_alternative<T>(state_); }
    explicit operator bool() const { return ok(); }

    T &value() & { return std::get<T>(state_); }
    const T &value() const & { return std::get<T>(state_); }
    T &&value() && { return std::get<T>(std::move(state_)); }
    T *operator->() { return &value(); }
    const T *operator->() const { return &value(); }
    T &operator*() { return value(); }
    const T &operator*() const { return value(); }

    const Error &error() const { return std::get<Error>(state_); }

private:
    std::variant<T, Error> state_;
};

// Result<void>: success, or an Error.
struct Ok {};
using Status = Result<Ok>;

inline Error makeError(ErrorCode code, std::string message)
{
    return Error{code, std::move(message)};
}

} // namespace overlayd
