#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <string>
#include <vector>

#include "plan/workers.hpp"

using namespace scaffold;

TEST(Workers, EveryWorkerRunsOnce) {
    std::vector<std::atomic<int>> ran(3);
    plan::run_workers(3, [&](int w) { ++ran[static_cast<std::size_t>(w)]; });
    for (const auto& r : ran) EXPECT_EQ(r.load(), 1);
}

// What a worker throws reaches the caller after all have ended; of two,
// the lower numbered worker's.
TEST(Workers, AFailureReachesTheCallerAfterAllEnd) {
    std::atomic<int> ended{0};
    try {
        plan::run_workers(3, [&](int w) {
            ++ended;
            if (w > 0) throw std::runtime_error("worker " + std::to_string(w));
        });
        FAIL() << "nothing thrown";
    } catch (const std::runtime_error& e) {
        EXPECT_EQ(std::string(e.what()), "worker 1");
    }
    EXPECT_EQ(ended.load(), 3);
}
