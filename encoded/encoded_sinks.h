// EncodedSinks: the [[sink]] tables that take the encoded stream rather than frames (recordings, pushes).
#pragma once

#include <vector>

#include "encoded/push_options.h"
#include "encoded/record_options.h"

namespace overlayd {

struct EncodedSinks {
    std::vector<RecordOptions> records;
    std::vector<PushOptions> pushes;

    bool empty() const { return records.empty() && pushes.empty(); }
    bool operator==(const EncodedSinks &) const = default;
};

} // namespace overlayd
