// Work shared among threads, with an exception thrown on any of them carried back to the caller:
// each worker catches what its work throws (an exception that leaves a std::thread's function
// calls std::terminate), the others stop at their next item, and the caller rethrows the first
// exception once every thread has finished. The catalog search (its stages and the evaluation of
// its candidates) and the sweep's points run on these.
#pragma once

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

namespace dynosize {

// The first exception thrown by any of a set of threads' work.
class FirstException {
 public:
  // Runs fn(); if it throws, keeps the exception (unless one is already kept) and returns false.
  template <typename F>
  bool Capture(F&& fn) noexcept {
    try {
      fn();
      return true;
    } catch (...) {
      const std::lock_guard<std::mutex> lock(mu_);
      if (!error_) error_ = std::current_exception();
      failed_.store(true, std::memory_order_relaxed);
      return false;
    }
  }
  // True once some work threw: the others poll it between items to stop early.
  bool failed() const { return failed_.load(std::memory_order_relaxed); }
  // Rethrows the kept exception, if any, and forgets it. Call after every thread has finished.
  void Rethrow() {
    std::exception_ptr e;
    {
      const std::lock_guard<std::mutex> lock(mu_);
      std::swap(e, error_);
      failed_.store(false, std::memory_order_relaxed);
    }
    if (e) std::rethrow_exception(e);
  }

 private:
  std::mutex mu_;
  std::exception_ptr error_;
  std::atomic<bool> failed_{false};
};

// fn(thread, i) for i in [0, n), i interleaved over `threads` threads (each i on one thread; the
// calling thread is thread 0). When fn throws, the threads stop at their next i and the first
// exception is rethrown here after all have joined.
template <typename F>
void ForEachOnThreads(std::size_t n, int threads, const F& fn) {
  threads = std::max(1, threads);
  FirstException error;
  auto work = [&](int tid) {
    error.Capture([&] {
      for (std::size_t i = static_cast<std::size_t>(tid); i < n && !error.failed(); i += static_cast<std::size_t>(threads)) {
        fn(tid, i);
      }
    });
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(work, t);
  work(0);
  for (std::thread& th : pool) th.join();
  error.Rethrow();
}

// Worker threads kept for many short jobs: Start hands every thread the same job, Wait returns
// when all have finished it. A job that throws is caught on its thread; failed() turns true (a
// job's loop polls it to stop early) and Wait rethrows the first exception. The pool stays
// usable after that.
class WorkerThreads {
 public:
  explicit WorkerThreads(int n) {
    for (int i = 0; i < n; ++i) threads_.emplace_back([this] { Loop(); });
  }
  ~WorkerThreads() {
    {
      std::lock_guard<std::mutex> lock(mu_);
      stop_ = true;
    }
    start_.notify_all();
    for (std::thread& t : threads_) t.join();
  }
  WorkerThreads(const WorkerThreads&) = delete;
  WorkerThreads& operator=(const WorkerThreads&) = delete;

  void Start(const std::function<void()>* job) {
    {
      std::lock_guard<std::mutex> lock(mu_);
      job_ = job;
      running_ = static_cast<int>(threads_.size());
      ++generation_;
    }
    start_.notify_all();
  }
  // Runs fn on the calling thread alongside the workers, its exception kept as theirs are.
  template <typename F>
  void RunHere(F&& fn) {
    error_.Capture(std::forward<F>(fn));
  }
  bool failed() const { return error_.failed(); }
  // Returns when every worker has finished the job; rethrows the first exception of the job's
  // run (on a worker or in RunHere).
  void Wait() {
    {
      std::unique_lock<std::mutex> lock(mu_);
      done_.wait(lock, [this] { return running_ == 0; });
    }
    error_.Rethrow();
  }

 private:
  void Loop() {
    long seen = 0;
    while (true) {
      const std::function<void()>* job = nullptr;
      {
        std::unique_lock<std::mutex> lock(mu_);
        start_.wait(lock, [&] { return stop_ || generation_ != seen; });
        if (stop_) return;
        seen = generation_;
        job = job_;
      }
      error_.Capture(*job);
      std::lock_guard<std::mutex> lock(mu_);
      if (--running_ == 0) done_.notify_one();
    }
  }
  std::mutex mu_;
  std::condition_variable start_, done_;
  const std::function<void()>* job_ = nullptr;
  long generation_ = 0;
  int running_ = 0;
  bool stop_ = false;
  std::vector<std::thread> threads_;
  FirstException error_;
};

}  // namespace dynosize
