// SPDX-License-Identifier: Apache-2.0
// EventLoop: a handler that throws (a bug) is reported and skipped; the loop and the other handlers go on.
#include "base/event_loop.h"

#include <stdexcept>
#include <string>
#include <sys/eventfd.h>
#include <unistd.h>
#include <vector>

#include <gtest/gtest.h>

namespace overlayd {
namespace {

TEST(EventLoop, AThrowingHandlerIsReportedAndTheLoopGoesOn)
{
    auto loop = EventLoop::create();
    ASSERT_TRUE(loop);
    std::vector<std::string> failures;
    loop->setFailureLog([&failures](const std::string &what) { failures.push_back(what); });
    UniqueFd bad(::eventfd(1, EFD_NONBLOCK | EFD_CLOEXEC)), good(::eventfd(1, EFD_NONBLOCK | EFD_CLOEXEC));
    int goodRuns = 0;
    ASSERT_TRUE(loop->add(bad.get(), [] { throw std::runtime_error("a bug in a handler"); }));
    ASSERT_TRUE(loop->add(good.get(), [&] {
        uint64_t count = 0;
        (void)!::read(good.get(), &count, sizeof(count));
        ++goodRuns;
    }));
    EXPECT_TRUE(loop->runOnce(1000));
    EXPECT_TRUE(loop->runOnce(0)); // the throwing handler's fd is still readable: it throws again
    EXPECT_EQ(goodRuns, 1);
    ASSERT_EQ(failures.size(), 2u);
    EXPECT_EQ(failures[0], "a bug in a handler");
}

} // namespace
} // namespace overlayd
