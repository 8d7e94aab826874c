// Optimizations as jobs of `dynosize serve`, for the page's progress bar and its Cancel button:
//   POST /api/jobs/optimize      the body of /api/optimize  -> 202 {"job": ID}
//   GET  /api/jobs/ID            {"job", "state": queued | running | done | failed, "seconds",
//                                 "progress": {"fraction", "searched", "pruned", "found",
//                                 "best_objective" (in the unit the CLI prints), "unit"},
//                                 "result": optimize --json when done, "error" when failed,
//                                 "pareto": {"unit", "evaluated", "all", "front"} when done:
//                                 [mass kg, objective] as optimize --plot's Pareto figure}
//   POST /api/jobs/ID/cancel     stops the search: it finishes with the best so far (its result
//                                 says "interrupted": true), as Ctrl-C does on the CLI
// A job runs on its own thread through the server's job queue (server/job_queue.h). At most
// max_jobs are kept; a finished job is forgotten, oldest first, when a new one needs its place
// (503 when every kept job is still running).
#pragma once

#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "server/api_routes.h"
#include "server/job_queue.h"

namespace dynosize::server {

class OptimizeJobs {
 public:
  OptimizeJobs(const ApiContext& context, JobQueue& queue, int max_jobs)
      : context_(context), queue_(queue), max_jobs_(max_jobs) {}
  ~OptimizeJobs();  // cancels every job and waits for its thread
  OptimizeJobs(const OptimizeJobs&) = delete;
  OptimizeJobs& operator=(const OptimizeJobs&) = delete;

  // Cancels every job (the server is stopping): each finishes with its best so far.
  void CancelAll();
  // The routes above (path under /api/jobs); null when the path is not one of them.
  std::unique_ptr<ApiAnswer> Handle(const std::string& method, const std::string& path, const std::string& body);

 private:
  struct Job;
  ApiAnswer Start(const std::string& body);
  ApiAnswer Status(const std::string& id);
  ApiAnswer Cancel(const std::string& id);
  bool MakeRoom();  // under mutex_: forget the oldest finished job when full; false when none is

  const ApiContext& context_;
  JobQueue& queue_;
  const int max_jobs_;
  std::mutex mutex_;
  std::map<std::string, std::shared_ptr<Job>> jobs_;
  long long started_ = 0;
};

}  // namespace dynosize::server
