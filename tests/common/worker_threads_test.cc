// Work on threads carries an exception back to the caller (common/worker_threads.h): without it,
// an exception leaving a worker thread's function calls std::terminate and ends the test binary.
#include "common/worker_threads.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstddef>
#include <functional>
#include <stdexcept>
#include <string>
#include <thread>

namespace dynosize {
namespace {

// Enough items that, had the other thread not stopped early, it would still be at work long after
// the throw (about a second of atomic increments): the count shows it stopped at its next item.
constexpr std::size_t kManyItems = 100'000'000;

TEST(ForEachOnThreadsTest, AWorkersExceptionReachesTheCaller) {
  std::atomic<std::size_t> done{0};
  const std::thread::id caller = std::this_thread::get_id();
  std::atomic<bool> thrown_on_worker{false};
  try {
    // Odd items run on thread 1, a worker; item 1 is its first.
    ForEachOnThreads(kManyItems, 2, [&](int tid, std::size_t i) {
      if (i == 1) {
        thrown_on_worker = tid == 1 && std::this_thread::get_id() != caller;
        throw std::runtime_error("item 1 failed");
      }
      ++done;
    });
    ADD_FAILURE() << "no exception reached the caller";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "item 1 failed");
  }
  EXPECT_TRUE(thrown_on_worker);
  EXPECT_LT(done.load(), kManyItems / 2) << "the caller's thread did not stop after the worker's exception";
}

TEST(ForEachOnThreadsTest, TheCallersExceptionWaitsForTheWorkers) {
  std::atomic<std::size_t> done{0};
  EXPECT_THROW(ForEachOnThreads(kManyItems, 3,
                                [&](int, std::size_t i) {
                                  if (i == 0) throw std::invalid_argument("item 0");
                                  ++done;
                                }),
               std::invalid_argument);
  EXPECT_LT(done.load(), kManyItems - 1);
}

TEST(ForEachOnThreadsTest, WithoutAnExceptionEveryItemRunsOnce) {
  std::atomic<std::size_t> sum{0};
  ForEachOnThreads(1000, 3, [&](int, std::size_t i) { sum += i; });
  EXPECT_EQ(sum.load(), 999u * 1000u / 2u);
}

TEST(WorkerThreadsTest, AJobsExceptionIsRethrownByWaitAndThePoolGoesOn) {
  WorkerThreads pool(2);
  std::atomic<std::size_t> next{0}, done{0};
  const std::thread::id caller = std::this_thread::get_id();
  // Every item on a worker throws; the caller's own share stops once one has.
  const std::function<void()> failing = [&] {
    if (std::this_thread::get_id() != caller) throw std::runtime_error("worker failed");
  };
  pool.Start(&failing);
  pool.RunHere([&] {
    for (std::size_t i = next++; i < kManyItems && !pool.failed(); i = next++) ++done;
  });
  try {
    pool.Wait();
    ADD_FAILURE() << "Wait did not rethrow the worker's exception";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "worker failed");
  }
  EXPECT_LT(done.load(), kManyItems);
  // The exception is gone once rethrown: the next job runs and Wait returns normally.
  std::atomic<int> ran{0};
  const std::function<void()> ok = [&] { ++ran; };
  pool.Start(&ok);
  pool.RunHere([&] { ++ran; });
  EXPECT_NO_THROW(pool.Wait());
  EXPECT_EQ(ran.load(), 3);
  EXPECT_FALSE(pool.failed());
}

TEST(WorkerThreadsTest, TheCallersExceptionIsRethrownAfterTheWorkersFinish) {
  WorkerThreads pool(1);
  std::atomic<bool> worker_finished{false};
  const std::function<void()> slow = [&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    worker_finished = true;
  };
  pool.Start(&slow);
  pool.RunHere([] { throw std::logic_error("caller failed"); });
  EXPECT_THROW(pool.Wait(), std::logic_error);
  EXPECT_TRUE(worker_finished);
}

}  // namespace
}  // namespace dynosize
