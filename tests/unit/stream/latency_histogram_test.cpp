// SPDX-License-Identifier: Apache-2.0
// LatencyHistogram: samples land in the bucket whose upper bound first covers them (Prometheus' le), and a
// quantile is the bound of the bucket holding it, checked against hand-counted samples.
#include <gtest/gtest.h>

#include "stream/latency_histogram.h"

using overlayd::LatencyHistogram;

TEST(LatencyHistogram, BucketsByUpperBoundAndQuantilesFromTheCounts)
{
    LatencyHistogram histogram;
    EXPECT_EQ(histogram.quantile(0.5), 0.0); // empty
    for (int i = 0; i < 98; ++i)
        histogram.add(0.004); // (0.002, 0.005]
    histogram.add(0.005);     // on a bound: that bucket (le = 0.005)
    histogram.add(3.0);       // beyond the last bound
    EXPECT_EQ(histogram.count, 100u);
    EXPECT_EQ(histogram.counts[2], 99u);
    EXPECT_EQ(histogram.counts.back(), 1u);
    EXPECT_NEAR(histogram.sum, 98 * 0.004 + 0.005 + 3.0, 1e-12);
    EXPECT_EQ(histogram.quantile(0.5), 0.005);
    EXPECT_EQ(histogram.quantile(0.99), 0.005);
    EXPECT_EQ(histogram.quantile(1.0), 1e9);
}
