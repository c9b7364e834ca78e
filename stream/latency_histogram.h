// SPDX-License-Identifier: Apache-2.0
// LatencyHistogram: how long frames took to reach one stage, in Prometheus-style buckets (seconds). Header-only:
// the GStreamer module fills some stages and the daemon's side the others.
#pragma once

#include <array>
#include <cstdint>

namespace overlayd {

struct LatencyHistogram {
    // Upper bounds, seconds: a frame interval at 30 fps is 0.033.
    static constexpr std::array<double, 12> kBounds{0.001, 0.002, 0.005, 0.01, 0.02, 0.033,
                                                    0.05,  0.1,   0.2,   0.5,  1.0,  2.0};
    std::array<uint64_t, kBounds.size() + 1> counts{}; // per bucket, not cumulative; the last is above 2 s
    double sum = 0;
    uint64_t count = 0;

    void add(double seconds)
    {
        size_t bucket = 0;
        while (bucket < kBounds.size() && seconds > kBounds[bucket])
            ++bucket;
        ++counts[bucket];
        sum += seconds;
        ++count;
    }
    // The upper bound of the bucket that holds the q-quantile (2 s and beyond: infinity as 1e9); 0 when empty.
    double quantile(double q) const
    {
        if (count == 0)
            return 0;
        const double rank = q * double(count);
        uint64_t seen = 0;
        for (size_t bucket = 0; bucket < kBounds.size(); ++bucket) {
            seen += counts[bucket];
            if (double(seen) >= rank)
                return kBounds[bucket];
        }
        return 1e9;
    }
};

} // namespace overlayd
