// SPDX-License-Identifier: Apache-2.0
#include "overlay/blend/native_runs.h"

namespace overlayd {

void NativeRuns::clear(size_t bytes, size_t runs)
{
    runs_.clear();
    values_.clear();
    inverseAlpha_.clear();
    values_.reserve(bytes + kBlendReadAhead);
    inverseAlpha_.reserve(bytes + kBlendReadAhead);
    runs_.reserve(runs);
}

void NativeRuns::beginRun(unsigned plane, unsigned row, unsigned byteOffset)
{
    // A placed layer's runs move by whole groups and whole plane rows.
    const unsigned rowShift = placement_.y / format_->planes[plane].verticalSubSampling;
    const unsigned byteShift = placement_.x / format_->pixelsPerGroup * format_->planes[plane].bytesPerGroup;
    runs_.push_back({plane, row + rowShift, byteOffset + byteShift, 0, uint32_t(values_.size())});
}

void NativeRuns::finish()
{
    values_.insert(values_.end(), kBlendReadAhead, 0);
    inverseAlpha_.insert(inverseAlpha_.end(), kBlendReadAhead, 255);
}

} // namespace overlayd
