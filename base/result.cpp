// SPDX-License-Identifier: Apache-2.0
// Names for error codes, used in messages and tests.
#include "base/result.h"

namespace overlayd {

const char *errorCodeName(ErrorCode code)
{
    switch (code) {
    case ErrorCode::InvalidArgument:
        return "invalid argument";
    case ErrorCode::DegenerateBasis:
        return "degenerate basis";
    case ErrorCode::NotOrthonormal:
        return "not orthonormal";
    case ErrorCode::UnknownFrame:
        return "unknown frame";
    case ErrorCode::DuplicateFrame:
        return "duplicate frame";
    case ErrorCode::CyclicFrames:
        return "cyclic frames";
    case ErrorCode::Unsupported:
        return "unsupported";
    case ErrorCode::NoConvergence:
        return "no convergence";
    case ErrorCode::NotFound:
        return "not found";
    case ErrorCode::Io:
        return "i/o error";
    case ErrorCode::Malformed:
        return "malformed";
    case ErrorCode::EndOfStream:
        return "end of stream";
    case ErrorCode::TryAgain:
        return "try again";
    case ErrorCode::DeviceLost:
        return "device lost";
    case ErrorCode::ConfigError:
        return "config error";
    }
    return "unknown error";
}

} // namespace overlayd
