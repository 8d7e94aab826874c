// The bounded job queue of `dynosize serve`: at most `running` solving requests at once, at most
// `waiting` more waiting for a slot; a request beyond both is refused at once (HTTP 503) instead of
// piling up threads and memory.
#pragma once

#include <condition_variable>
#include <mutex>

namespace dynosize::server {

class JobQueue {
 public:
  JobQueue(int running, int waiting) : max_running_(running), max_waiting_(waiting) {}

  // A slot held for the lifetime of the ticket (RAII); `admitted()` is false when the queue was
  // full and the request must be refused.
  class Ticket {
   public:
    explicit Ticket(JobQueue& q) : q_(q), admitted_(q.Enter()) {}
    ~Ticket() {
      if (admitted_) q_.Leave();
    }
    Ticket(const Ticket&) = delete;
    Ticket& operator=(const Ticket&) = delete;
    bool admitted() const { return admitted_; }

   private:
    JobQueue& q_;
    bool admitted_;
  };

  int running() const;
  int waiting() const;
  int max_running() const { return max_running_; }
  int max_waiting() const { return max_waiting_; }

 private:
  bool Enter();  // false when running and waiting are both full; else blocks until a slot is free
  void Leave();
  const int max_running_, max_waiting_;
  mutable std::mutex m_;
  std::condition_variable free_;
  int running_ = 0, waiting_ = 0;
};

}  // namespace dynosize::server
