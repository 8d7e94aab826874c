#include "server/job_queue.h"

namespace dynosize::server {

bool JobQueue::Enter() {
  std::unique_lock<std::mutex> lock(m_);
  if (running_ >= max_running_) {
    if (waiting_ >= max_waiting_) return false;
    ++waiting_;
    free_.wait(lock, [this] { return running_ < max_running_; });
    --waiting_;
  }
  ++running_;
  return true;
}

void JobQueue::Leave() {
  {
    const std::lock_guard<std::mutex> lock(m_);
    --running_;
  }
  free_.notify_one();
}

int JobQueue::running() const {
  const std::lock_guard<std::mutex> lock(m_);
  return running_;
}

int JobQueue::waiting() const {
  const std::lock_guard<std::mutex> lock(m_);
  return waiting_;
}

}  // namespace dynosize::server
