#include "server/jobs.h"

#include <atomic>
#include <chrono>
#include <random>
#include <thread>

#include "api/mission_catalog.h"
#include "common/error.h"
#include "common/json_file.h"
#include "optimization/search.h"
#include "report/mission_report.h"

namespace dynosize::server {

struct OptimizeJobs::Job {
  std::string id;
  long long order = 0;  // started as the n-th job (the oldest finished job is forgotten first)
  std::atomic<bool> cancel{false};
  std::chrono::steady_clock::time_point t0 = std::chrono::steady_clock::now();
  std::thread thread;
  // Under `m`:
  std::mutex m;
  std::string state = "queued";
  SearchProgress progress;
  double display_best = 0.0;
  std::string unit;
  Json result, pareto;
  ApiAnswer error;
};

namespace {

// 128 random bits in hex: a job's id is not guessable from another's.
std::string NewJobId() {
  static std::mutex m;
  static std::random_device device;
  static std::mt19937_64 gen(device());
  const std::lock_guard<std::mutex> lock(m);
  static const char* kHex = "0123456789abcdef";
  std::string id;
  for (int word = 0; word < 2; ++word) {
    std::uint64_t v = gen();
    for (int i = 0; i < 16; ++i, v >>= 4) id.push_back(kHex[v & 0xFu]);
  }
  return id;
}

ApiAnswer JsonAnswer(int status, const Json& j) { return {status, DumpJson(j)}; }

// The page's Pareto chart (report/mission_report.h ParetoPointsOf, as optimize --plot draws it):
// [mass kg, objective] pairs, every evaluated combination (an even sample of kMaxParetoPoints
// when there are more) and the front.
constexpr std::size_t kMaxParetoPoints = 20000;
Json ParetoJson(const Mission& mission, const SearchResult& s) {
  const ParetoPoints p = ParetoPointsOf(mission, s);
  Json all = Json::array(), front = Json::array();
  const std::size_t stride = p.all.size() / kMaxParetoPoints + 1;
  for (std::size_t i = 0; i < p.all.size(); i += stride) all.push_back({p.all[i].first, NumberOrNull(p.all[i].second)});
  for (const auto& [mass, objective] : p.front) front.push_back({mass, NumberOrNull(objective)});
  Json j;
  j["unit"] = DisplayUnit(mission);
  j["evaluated"] = p.all.size();
  j["all"] = std::move(all);
  j["front"] = std::move(front);
  return j;
}

}  // namespace

OptimizeJobs::~OptimizeJobs() {
  std::map<std::string, std::shared_ptr<Job>> jobs;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    jobs.swap(jobs_);
  }
  for (auto& [id, job] : jobs) job->cancel.store(true);
  for (auto& [id, job] : jobs) {
    if (job->thread.joinable()) job->thread.join();
  }
}

void OptimizeJobs::CancelAll() {
  const std::lock_guard<std::mutex> lock(mutex_);
  for (auto& [id, job] : jobs_) job->cancel.store(true);
}

bool OptimizeJobs::MakeRoom() {
  if (static_cast<int>(jobs_.size()) < max_jobs_) return true;
  std::shared_ptr<Job> oldest;
  for (const auto& [id, job] : jobs_) {
    const std::lock_guard<std::mutex> lock(job->m);
    if ((job->state == "done" || job->state == "failed") && (!oldest || job->order < oldest->order)) oldest = job;
  }
  if (!oldest) return false;
  jobs_.erase(oldest->id);
  if (oldest->thread.joinable()) oldest->thread.join();  // finished: returns at once
  return true;
}

ApiAnswer OptimizeJobs::Start(const std::string& body) {
  OptimizeWork work = OptimizeWorkOf(context_, body);  // a bad body is a 400 now, not a failed job
  auto job = std::make_shared<Job>();
  job->id = NewJobId();
  job->unit = DisplayUnit(work.mission);
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (!MakeRoom()) {
      return {503, ErrorBody("the server is busy: " + std::to_string(max_jobs_) +
                                 " optimize jobs are kept and none has finished; cancel one or try again",
                             static_cast<int>(ExitCode::kUsage))};
    }
    job->order = ++started_;
    jobs_[job->id] = job;
  }
  const Catalog* catalog = context_.catalog;
  job->thread = std::thread([this, job, catalog, work = std::move(work)]() mutable {
    const JobQueue::Ticket ticket(queue_);  // waits for a slot like any solving request
    if (!ticket.admitted()) {
      const std::lock_guard<std::mutex> lock(job->m);
      job->state = "failed";
      job->error = {503, ErrorBody("the server is busy: its job queue is full; try again",
                                   static_cast<int>(ExitCode::kUsage))};
      return;
    }
    {
      const std::lock_guard<std::mutex> lock(job->m);
      job->state = "running";
    }
    work.options.stop = &job->cancel;  // the server's stop reaches it through CancelAll
    const Mission& mission = work.mission;
    work.options.progress = [job, &mission](const SearchProgress& p) {
      const std::lock_guard<std::mutex> lock(job->m);
      job->progress = p;
      job->display_best = p.has_best ? DisplayObjective(mission, p.best_objective) : 0.0;
    };
    try {
      const api::MissionCatalog cat(*catalog, mission);  // with the mission's sized propellers
      const SearchResult s = SearchCatalog(mission, cat.get(), work.options);
      Json result = SearchResultJson(mission, s);
      CheckJsonFinite(result, "optimize result");
      Json pareto = ParetoJson(mission, s);
      const std::lock_guard<std::mutex> lock(job->m);
      job->result = std::move(result);
      job->pareto = std::move(pareto);
      job->state = "done";
    } catch (const std::exception& e) {
      const auto* err = dynamic_cast<const Error*>(&e);
      const std::lock_guard<std::mutex> lock(job->m);
      job->state = "failed";
      job->error = {err ? 400 : 500, ErrorBody(err ? e.what() : std::string("internal error: ") + e.what(),
                                               static_cast<int>(err ? err->code() : ExitCode::kInternal))};
    }
  });
  Json j;
  j["job"] = job->id;
  return JsonAnswer(202, j);
}

ApiAnswer OptimizeJobs::Status(const std::string& id) {
  std::shared_ptr<Job> job;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    const auto it = jobs_.find(id);
    if (it != jobs_.end()) job = it->second;
  }
  if (!job) {
    return {404, ErrorBody("job '" + id.substr(0, 64) + "': no such job (finished jobs are forgotten when newer ones need "
                                                       "their place)",
                           static_cast<int>(ExitCode::kUsage))};
  }
  const std::lock_guard<std::mutex> lock(job->m);
  Json j;
  j["job"] = job->id;
  j["state"] = job->state;
  j["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - job->t0).count();
  Json p;
  p["fraction"] = job->progress.fraction;
  p["searched"] = job->progress.searched;
  p["pruned"] = job->progress.pruned;
  p["found"] = job->progress.found;
  p["best_objective"] = job->progress.has_best ? Json(job->display_best) : Json(nullptr);
  p["unit"] = job->unit;
  j["progress"] = p;
  j["cancelled"] = job->cancel.load();
  if (job->state == "done") {
    j["result"] = job->result;
    j["pareto"] = job->pareto;
  }
  if (job->state == "failed") j["error"] = Json::parse(job->error.body);
  return JsonAnswer(200, j);
}

ApiAnswer OptimizeJobs::Cancel(const std::string& id) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    const auto it = jobs_.find(id);
    if (it != jobs_.end()) it->second->cancel.store(true);
  }
  return Status(id);
}

std::unique_ptr<ApiAnswer> OptimizeJobs::Handle(const std::string& method, const std::string& path,
                                                const std::string& body) {
  const std::string prefix = "/api/jobs/";
  if (path.rfind(prefix, 0) != 0) return nullptr;
  const std::string rest = path.substr(prefix.size());
  const std::string cancel = "/cancel";
  const auto answer = [](ApiAnswer a) { return std::make_unique<ApiAnswer>(std::move(a)); };
  const auto wrong_method = [&](const char* want) {
    return answer({405, ErrorBody(path + ": use " + want, static_cast<int>(ExitCode::kUsage))});
  };
  try {
    if (rest == "optimize") return method == "POST" ? answer(Start(body)) : wrong_method("POST");
    if (rest.size() > cancel.size() && rest.compare(rest.size() - cancel.size(), cancel.size(), cancel) == 0) {
      if (method != "POST") return wrong_method("POST");
      return answer(Cancel(rest.substr(0, rest.size() - cancel.size())));
    }
    if (rest.find('/') == std::string::npos) return method == "POST" ? wrong_method("GET") : answer(Status(rest));
  } catch (const Error& e) {
    return answer({e.code() == ExitCode::kInternal ? 500 : 400, ErrorBody(e.what(), static_cast<int>(e.code()))});
  }
  return nullptr;
}

}  // namespace dynosize::server
