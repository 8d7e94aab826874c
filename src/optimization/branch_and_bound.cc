// Stage 5 of the catalog search (search_stages.h): the candidate pairs best bound first, each
// pair's ESCs with R5, R9, R10 and R12, every combination not pruned scored exactly; and
// SearchOneGroup, stages 0-5 for one free group (docs/search.md).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <vector>

#include "common/error.h"
#include "common/worker_threads.h"
#include "optimization/components.h"
#include "optimization/pair_bounds.h"
#include "optimization/rule_counts.h"
#include "optimization/search_stages.h"
#include "optimization/top_results.h"

namespace dynosize {

namespace {

using namespace search_internal;

constexpr double kInf = std::numeric_limits<double>::infinity();

// Stage 5: the candidate pairs best bound first, each pair's ESCs with R5, every combination
// not pruned scored exactly.
class BranchAndBound {
 public:
  // cutoff: only results scoring below it are wanted (the joint search's N-th best, G2).
  // t0: the search's start (SearchResult::first_result_s).
  BranchAndBound(const SearchContext& ctx, const SearchOptions& opt, CandidateStream* stream, SearchResult* out,
                 std::chrono::steady_clock::time_point t0, double cutoff = kInf)
      : t0_(t0),
        ctx_(ctx),
        opt_(opt),
        stream_(*stream),
        open_at_start_(stream->open_combinations()),
        out_(out),
        relaxed_(*ctx.mission),
        facts_(FactsOf(*ctx.mission, ctx.free_group)),
        board_(opt.top_n, opt.distinct_designs, cutoff) {
    // The virtual ESC (and so the class check) uses the mission without min_hover_throttle: a
    // real ESC's resistance and mass raise the throttle, so that lower limit is the one
    // constraint the virtual ESC may fail when a real one passes (R5). Relaxing it keeps the
    // check a bound. The thrust-to-weight is left out of it too (any relaxation keeps it a
    // bound): its full-throttle solve costs a third of a simulation, and the few real ESCs
    // that reach the evaluation check it.
    relaxed_.constraints.min_hover_throttle = 0.0;
    relaxed_.constraints.prop_below_data_factor = 0.0;  // a heavier real ESC turns the rotor faster
    relaxed_.constraints.min_thrust_to_weight = 0.0;
  }

  void Run();
  // R14 (docs/search.md#r14): the deferred combinations of the final top N designs solved with
  // the final threshold; those below it join their design's alternatives.
  void ResolveDeferred();
  // Solves the top N again with explain (warnings, the solver's report, the designer's summary,
  // propeller notes): Process scores without them (text for results nobody reads), each with
  // the cutoff it had, so the numbers are the same.
  void Explain() const;
  long long virtual_evaluations() const { return virtual_evals_; }

 private:
  struct Outcome {
    std::vector<std::pair<Combination, MissionResult>> results;
    std::vector<double> cutoffs;  // per result, the cutoff its Solve had
    // Combinations proven to score no better than their design's best (R14): solved at the end
    // when their design is in the final top N (ResolveDeferred).
    std::vector<std::pair<Combination, const char*>> deferred;  // and the rule it is counted under
    RuleCounts pruned;
    long long searched = 0, virtual_evals = 0;
  };

  // Candidates in CandidateBefore order (best bound first, a strict total order). The search
  // usually stops after a small fraction of them, so they are drawn on demand from the stream
  // (stage 4 bounds a pair only when it may come next), with the N-th best score as its
  // cutoff: the search stops at the first pair not below it (the threshold only falls), and a
  // pair that comes after it is never drawn.
  const Candidate* CandidateAt(std::size_t i) {  // the i-th best, or null
    Candidate c;
    while (base_ + ordered_.size() <= i && stream_.Next(NthBest(), &c)) ordered_.push_back(c);
    return i < base_ + ordered_.size() ? &ordered_[i - base_] : nullptr;
  }
  double NthBest() const { return board_.Threshold(); }
  void Insert(const Combination& c, MissionResult&& r, double cutoff);
  void Process(const Candidate& cand, TopScores top, Outcome* o) const;
  void RealEscs(const std::vector<int>& rated, Combination* c, const PropModel* model, TopScores* top,
                Outcome* o) const;
  // The free group's ESC of a combination.
  void SetEsc(Combination* x, const EscEntry* e) const {
    x->esc = e;
    if (!x->groups.empty()) x->groups[ctx_.free_group].esc = e;
  }
  // Stops the search before the chunk at ci when a stop was requested and work is left.
  bool StopAt(std::size_t ci, double threshold);
  void ReportProgress(std::size_t ci);

  const std::chrono::steady_clock::time_point t0_;
  const SearchContext& ctx_;
  const SearchOptions& opt_;
  CandidateStream& stream_;
  long long open_at_start_ = 0;  // the stream's open combinations before the first draw (progress)
  std::vector<Candidate> ordered_;  // drawn candidates from index base_ on (earlier ones done)
  std::size_t base_ = 0;
  SearchResult* out_;
  Mission relaxed_;
  MissionFacts facts_;
  TopResults board_;  // the top N so far (top_results.h); out_->best at the end
  std::map<EntryKey, std::vector<std::pair<Combination, const char*>>> deferred_;  // per design, in candidate order (R14)
  long long virtual_evals_ = 0;
};

void BranchAndBound::Insert(const Combination& c, MissionResult&& r, double cutoff) {
  if (!r.feasible) return;
  if (!std::isfinite(out_->first_result_s)) {
    out_->first_result_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
  }
  out_->evaluated_mass_objective.emplace_back(r.propulsion_mass_kg, r.objective);
  board_.Add(RankedCombination{c, std::move(r), {}}, cutoff);
}

void BranchAndBound::ResolveDeferred() {
  const double threshold = board_.Threshold();
  std::vector<EntryKey> designs;
  for (const auto& entry : board_.scores().entries()) designs.push_back(entry.first);
  for (const EntryKey& design : designs) {
    const auto it = deferred_.find(design);
    if (it == deferred_.end()) continue;
    for (const auto& [c, rule] : it->second) {
      const PropModel* model = ctx_.models[static_cast<std::size_t>(c.prop - ctx_.catalog->props().data())].get();
      MissionResult r = MissionEvaluator(*ctx_.mission, c, model, &ctx_.fixed_model_ptrs).Solve(threshold, false, false, true);
      if (r.bounded_out) continue;  // counted as pruned when deferred
      --out_->pruned_by[rule];  // solved after all
      ++out_->searched;
      Insert(c, std::move(r), threshold);
    }
  }
  deferred_.clear();
}

void BranchAndBound::Explain() const {
  std::vector<double> cutoffs;
  out_->best = board_.Sorted(&cutoffs);
  out_->nth_best_score = board_.Threshold();
  for (std::size_t i = 0; i < out_->best.size(); ++i) {
    RankedCombination& b = out_->best[i];
    const PropModel* model = b.combination.prop == nullptr
                                 ? nullptr
                                 : ctx_.models[static_cast<std::size_t>(b.combination.prop - ctx_.catalog->props().data())].get();
    b.result = MissionEvaluator(*ctx_.mission, b.combination, model, &ctx_.fixed_model_ptrs).Solve(cutoffs[i]);
  }
}

// R5 for the real ESCs of a class that passed R3, R9, R10, R12 and the virtual ESC (`rated`,
// lightest first): each solved exactly unless an ESC already solved dominates it and cannot
// enter the top N (docs/search.md#r5). Distinct designs: an ESC of a design already in `top`
// is solved with that design's best as its cutoff (R14, docs/search.md#r14); one proven no
// better, and those it dominates, are deferred (Outcome::deferred) instead of solved.
void BranchAndBound::RealEscs(const std::vector<int>& rated, Combination* c, const PropModel* model, TopScores* top,
                              Outcome* o) const {
  const Mission& m = *ctx_.mission;
  const auto& escs = ctx_.catalog->escs();
  const EntryKey design = top->distinct_designs() ? KeyOf(*c, true) : EntryKey{};
  auto design_best = [&]() {  // the design's best score in `top` (kInf when not there or not counting designs)
    if (design.empty()) return kInf;
    for (const auto& entry : top->entries()) {
      if (entry.first == design) return entry.second;
    }
    return kInf;
  };
  // What an ESC already solved proves of those it dominates (R5): nothing; that they cannot
  // enter the top N; that they score no better than the design's best so far (R14).
  enum Proof { kNothing, kOut, kNotBelowDesign };
  std::vector<std::pair<int, Proof>> done;
  for (int e : rated) {
    Proof skip = kNothing;
    for (const auto& d : done) {
      if (d.second != kNothing && EscDominates(escs[d.first], escs[e])) {
        skip = d.second;
        if (skip == kOut) break;
      }
    }
    SetEsc(c, &escs[e]);
    if (skip != kNothing) {
      o->pruned.Add("esc_dominated", 1);
      if (skip == kNotBelowDesign) o->deferred.emplace_back(*c, "esc_dominated");
      continue;
    }
    const double threshold = top->Threshold();
    const double best = design_best();
    const double cutoff = std::min(threshold, best);
    const MissionEvaluator eval(m, *c, model, &ctx_.fixed_model_ptrs);
    if (MissionResult w; eval.DataWindowRefuses(true, &w)) {  // R12, before a solve
      const bool above = w.violations[0].constraint == "prop_above_data";
      o->pruned.Add(above ? "prop_above_data" : "prop_below_data", 1);
      done.emplace_back(e, RulesOutDominatedEscs(w) ? kOut : kNothing);  // below: a heavier ESC may meet it
      continue;
    }
    MissionResult r = eval.Solve(cutoff, false, false, true);
    if (r.bounded_out) {
      o->pruned.Add("objective_bound", 1);
      if (cutoff < threshold) o->deferred.emplace_back(*c, "objective_bound");
      done.emplace_back(e, cutoff < threshold ? kNotBelowDesign : kOut);
      continue;
    }
    ++o->searched;
    Proof proof = kNothing;
    if (!r.feasible) {
      proof = RulesOutDominatedEscs(r) ? kOut : kNothing;
    } else if (!(r.score < threshold)) {
      proof = kOut;
    } else if (!(r.score < best)) {
      proof = kNotBelowDesign;
    }
    done.emplace_back(e, proof);
    if (r.feasible) {
      top->Add(KeyOf(*c, top->distinct_designs()), r.score);
      o->results.emplace_back(*c, std::move(r));
      o->cutoffs.push_back(cutoff);
    }
  }
}

// Rule R5 (docs/search.md#r5): an ESC of the same class that is no lighter, no lower in
// resistance and no higher in rating scores no better (M2, M3); a class's virtual ESC (no
// resistance, the lightest mass) that cannot enter the top N rules out the whole class.
// One candidate pair against the N best scores when its chunk started (`top`, updated with
// this pair's own results, so that the threshold tightens within the pair exactly as it would
// in a sequential search): virtual ESC per class first (R5), then the real ESCs, lightest first,
// skipping dominated ones. Pruning against a threshold at least the final N-th best is safe.
void BranchAndBound::Process(const Candidate& cand, TopScores top, Outcome* o) const {
  const Mission& m = *ctx_.mission;
  const auto& escs = ctx_.catalog->escs();
  const double margin = 1.0 - m.constraints.current_margin;
  auto threshold_now = [&]() { return top.Threshold(); };
  auto local_prune = [&](const char* rule, long long n) { o->pruned.Add(rule, n); };
  const BatteryOption& bo = ctx_.options[cand.option];
  const PropModel* model = ctx_.models[cand.prop].get();
  Combination c{&ctx_.catalog->motors()[cand.motor], nullptr, &ctx_.catalog->props()[cand.prop], bo.entry, bo.cells, {}};
  if (!ctx_.fixed_parts.empty()) {
    c.groups = ctx_.fixed_parts;
    c.groups[ctx_.free_group].motor = c.motor;
    c.groups[ctx_.free_group].prop = c.prop;
  }
  const MotorParams mp = ScenarioMotorParams(*c.motor, m, nullptr, nullptr);  // as MotorSetUp (R9)
  std::vector<int> rated;  // per class, reused
  for (std::size_t cl = 0; cl < ctx_.escs.classes.size(); ++cl) {
    const std::vector<int>& list = ctx_.escs.per_option[cand.option][cl];
    if (list.empty()) continue;
    // R3: ESCs rated below the Irms lower bound. How many pass, and the lightest that does,
    // by binary search (EscTable's sorted currents and running maximum); the list of those
    // that pass is built only for the classes R10 lets through.
    auto below_r3 = [&](double current_a) { return current_a * margin < cand.irms_lb; };
    const std::vector<double>& ascending = ctx_.escs.currents_ascending[cand.option][cl];
    std::size_t n_rated = static_cast<std::size_t>(
        ascending.end() - std::partition_point(ascending.begin(), ascending.end(), below_r3));
    local_prune("esc_current", static_cast<long long>(list.size() - n_rated));
    if (n_rated == 0) continue;
    const std::vector<double>& running_max = ctx_.escs.running_max_current[cand.option][cl];
    const int lightest_rated =
        list[static_cast<std::size_t>(std::partition_point(running_max.begin(), running_max.end(), below_r3) -
                                      running_max.begin())];
    // R5's virtual ESC of the rated ESCs (only what the evaluator reads: no copy of the JSON).
    EscEntry virt;
    virt.id = "virtual";
    virt.params = escs[lightest_rated].params;
    virt.params.resc_ohm = 0.0;
    virt.params.max_current_a = kInf;
    virt.mass_kg = EscMassKg(escs[lightest_rated]);
    // R10: segment by segment, with the virtual ESC's drive and mass; true when it prunes the
    // class. First with every rated ESC (it refuses most classes, and R9 is then not needed),
    // again after R9 when R9 took the lightest away (a heavier virtual ESC: a tighter bound).
    auto segmentwise_prunes = [&]() {
      const char* rule = nullptr;
      const double t_max = ThrottleLimit(m.constraints, virt.params.tr_sat);
      const double threshold = threshold_now();
      const double b = SegmentwiseBoundPieces(ctx_, facts_, mp, Drive(mp, virt.params), t_max, cand.motor, cand.prop,
                                              cand.option, *virt.mass_kg, threshold, &rule);
      if (!rule && b < threshold) return false;
      local_prune(rule ? rule : "objective_bound", static_cast<long long>(n_rated));
      return true;
    };
    // Drops the rated ESCs that `fails` (counted under `rule`); true when that settles the class:
    // none is left, or R10 prunes it again with the lightest left (a heavier virtual ESC). The
    // lists are sorted by mass (BuildEscTable) and `rated` keeps their order.
    auto drop_escs = [&](const char* rule, auto&& fails) {
      const std::size_t before = rated.size();
      rated.erase(std::remove_if(rated.begin(), rated.end(), fails), rated.end());
      local_prune(rule, static_cast<long long>(before - rated.size()));
      if (rated.empty()) return true;
      n_rated = rated.size();
      const double kg = EscMassKg(escs[rated.front()]);
      if (kg == *virt.mass_kg) return false;
      virt.mass_kg = kg;
      return segmentwise_prunes();
    };
    if (segmentwise_prunes()) continue;
    rated.clear();
    for (int e : list) {
      if (!below_r3(EscReachCurrentA(escs[e]))) rated.push_back(e);
    }
    // R9, per ESC; skipped when the class's most favourable case (its lightest mass and least
    // resistance, which give the lowest throttle bound: M1-M3) is not below the limit.
    EscEntry least;
    least.params = escs[rated.front()].params;
    least.mass_kg = *virt.mass_kg;
    for (int e : rated) least.params.resc_ohm = std::min(least.params.resc_ohm, escs[e].params.resc_ohm);
    if (HoverThrottleBelowLimit(ctx_, facts_, mp, cand.motor, cand.prop, cand.option, least) &&
        drop_escs("min_hover_throttle", [&](int e) {
          return HoverThrottleBelowLimit(ctx_, facts_, mp, cand.motor, cand.prop, cand.option, escs[e]);
        })) {
      continue;
    }
    // The fixed groups' mass floor per ESC (R7, R6; FixedMassFloorRule): the lightest ESCs fail it
    // first.
    const double motor_kg = *c.motor->mass_kg, prop_kg = ctx_.grids[static_cast<std::size_t>(cand.prop)].mass_kg;
    if (const char* rule = FixedMassFloorRule(ctx_, cand.option, motor_kg, prop_kg, *virt.mass_kg);
        rule && drop_escs(rule, [&](int e) {
          return FixedMassFloorRule(ctx_, cand.option, motor_kg, prop_kg, EscMassKg(escs[e])) != nullptr;
        })) {
      continue;
    }
    // The fixed groups' mass ceiling per ESC (FixedMassCeilingRule): the heaviest ESCs fail it
    // first.
    if (const char* rule = FixedMassCeilingRule(ctx_, cand.option, motor_kg, prop_kg, ctx_.escs.max_mass_kg[cand.option]);
        rule && drop_escs(rule, [&](int e) {
          return FixedMassCeilingRule(ctx_, cand.option, motor_kg, prop_kg, EscMassKg(escs[e])) != nullptr;
        })) {
      continue;
    }
    // R12 per ESC (the window's bottom): the lightest ESCs fail it first (M3).
    if (HoverSpeedBelowWindow(ctx_, facts_, cand.motor, cand.prop, cand.option, *virt.mass_kg) &&
        drop_escs("prop_below_data", [&](int e) {
          return HoverSpeedBelowWindow(ctx_, facts_, cand.motor, cand.prop, cand.option, EscMassKg(escs[e]));
        })) {
      continue;
    }
    {
      Combination vc = c;
      SetEsc(&vc, &virt);
      const double threshold = threshold_now();
      const MissionEvaluator virtual_eval(relaxed_, vc, model, &ctx_.fixed_model_ptrs);
      // R12: above the window at the lightest vehicle; every ESC of the class is heavier (M3).
      if (MissionResult w; virtual_eval.DataWindowRefuses(false, &w)) {
        local_prune("prop_above_data", static_cast<long long>(rated.size()));
        continue;
      }
      const MissionResult vr = virtual_eval.Solve(threshold, false, true, true);
      ++o->virtual_evals;
      if (vr.bounded_out || !vr.feasible || !(vr.score < threshold)) {
        local_prune(vr.bounded_out || vr.feasible ? "objective_bound" : "infeasible_bound",
                    static_cast<long long>(rated.size()));
        continue;
      }
    }
    RealEscs(rated, &c, model, &top, o);
  }
}

// Chunks of candidates evaluated on the worker threads against the threshold at the chunk's
// start, merged in candidate order: the answer and the counts do not depend on timing. Ipopt
// (the shaft segments' solver, MUMPS) is not thread-safe: missions with a free shaft speed run
// on one thread.
bool BranchAndBound::StopAt(std::size_t ci, double threshold) {
  const Candidate* next = CandidateAt(ci);
  if (!next || !(next->bound < threshold)) return false;  // nothing left: the search ends anyway
  // The candidates come best bound first: the next one's bound is below every later one's, and
  // every combination of a pair scores at least the pair's bound (R4, R11).
  out_->interrupted = true;
  out_->unsettled_bound_score = next->bound;
  out_->unsettled = stream_.open_combinations();
  for (std::size_t i = ci; i < base_ + ordered_.size(); ++i) {
    out_->unsettled += ctx_.escs.rated[static_cast<std::size_t>(ordered_[i - base_].option)];
  }
  return true;
}

// The share of the work done: the candidate pairs drawn against those drawn plus an upper bound
// of those still to draw below the N-th best (CandidateStream::PairsLeftBelow). It moves with
// the work (the bound gap does not: on the capacity-sized quadcopter the gap was 95 % closed
// after 3 s of 10, as the bounds crowd just below the threshold).
void BranchAndBound::ReportProgress(std::size_t ci) {
  if (!opt_.progress) return;
  SearchProgress p;
  const Candidate* next = CandidateAt(ci);
  const double threshold = NthBest();
  if (!next || !(next->bound < threshold)) {
    p.fraction = 1.0;
  } else {
    const double drawn = static_cast<double>(ci);
    const double left = static_cast<double>(base_ + ordered_.size() - ci + stream_.PairsLeftBelow(threshold));
    p.fraction = drawn / (drawn + left);
    if (std::isfinite(next->bound)) {
      p.has_bound = true;
      p.bound_objective = ObjectiveOfScore(ctx_.mission->objective.type, next->bound);
    }
  }
  p.searched = out_->searched;
  for (const auto& [rule, n] : out_->pruned_by) p.pruned += n;
  p.has_best = !board_.empty();
  p.found = board_.size();
  p.best_objective = board_.best_objective();
  opt_.progress(p);
}

void BranchAndBound::Run() {
  const Mission& m = *ctx_.mission;
  const int workers = NeedsOneThread(m) ? 1 : std::max(1, opt_.threads);
  constexpr std::size_t kMaxChunk = 128;
  std::size_t chunk = 2;  // grows while the threshold settles
  // Kept for the whole search: a chunk of candidates lasts about a millisecond, too short to
  // start and join a thread per chunk (docs/search.md#constants).
  WorkerThreads pool(workers - 1);
  std::size_t ci = 0;
  for (;;) {
    ReportProgress(ci);
    const double threshold = NthBest();
    const bool over_budget =
        opt_.evaluation_budget > 0 && out_->searched + virtual_evals_ >= opt_.evaluation_budget;
    if ((over_budget || StopRequested(opt_)) && StopAt(ci, threshold)) break;
    const TopScores top = board_.scores();
    std::size_t end = ci;
    while (end - ci < chunk && CandidateAt(end) && CandidateAt(end)->bound < threshold) ++end;
    // Distinct designs: a pair is one design, so its own results cannot tighten its threshold
    // (TopScores): while fewer than N designs are known every ESC of a chunk's pairs is scored,
    // so the chunks stay small until the threshold is finite (the capacity-sized quadcopter:
    // 28 s before its first threshold with growing chunks).
    chunk = opt_.distinct_designs && !std::isfinite(threshold) ? chunk : std::min(kMaxChunk, 2 * chunk);
    if (end == ci) {  // R4: every later candidate has a bound at least as bad
      // Those never drawn and those drawn for the next chunk (the stream draws ahead).
      long long undrawn = stream_.open_combinations();
      for (std::size_t i = ci; i < base_ + ordered_.size(); ++i) {
        undrawn += ctx_.escs.rated[static_cast<std::size_t>(ordered_[i - base_].option)];
      }
      out_->pruned_by["objective_bound"] += undrawn;
      break;
    }
    std::vector<Outcome> outs(end - ci);
    // The chunk's candidates, copied: while the other workers start on them, this thread draws
    // the next chunk's from the stream (bounding a motor's next batch is serial work), with the
    // threshold before this chunk's results (at least the final one: the stream only draws
    // more, and a drawn pair not processed is counted when the search stops), then joins them.
    const std::vector<Candidate> cands(ordered_.begin() + static_cast<std::ptrdiff_t>(ci - base_),
                                       ordered_.begin() + static_cast<std::ptrdiff_t>(end - base_));
    // Each worker takes the next unprocessed candidate (one exact evaluation can cost as much
    // as a thousand pruned pairs: a fixed split leaves a thread idle).
    std::atomic<std::size_t> next{0};
    // An exception of one evaluation stops the others at their next candidate; Wait rethrows it.
    // A stop (SIGINT, the time limit) too, checked before a candidate is taken: a chunk of
    // solves with a free airspeed can last seconds. The candidates are taken in order and each
    // taken one is finished, so those done are the chunk's first min(next, size), and the rest
    // stay drawn for StopAt to count as unsettled.
    auto run = [&]() {
      while (!pool.failed() && !StopRequested(opt_)) {
        const std::size_t i = next++;
        if (i >= cands.size()) break;
        Process(cands[i], top, &outs[i]);
      }
    };
    const std::function<void()> job = run;
    pool.Start(&job);
    // On one thread too: the stream bounds a motor's next batch against the cutoff of the
    // moment it is drawn, and the pairs a rule removes are counted then, so the draws must
    // come at the same moments whatever the number of threads (the counts do not depend on it).
    pool.RunHere([&] {
      CandidateAt(end + chunk - 1);
      run();
    });
    pool.Wait();
    end = ci + std::min(next.load(), cands.size());  // fewer only after a stop
    outs.resize(end - ci);
    for (Outcome& o : outs) {
      o.pruned.MergeInto(&out_->pruned_by);
      out_->searched += o.searched;
      virtual_evals_ += o.virtual_evals;
      for (std::size_t j = 0; j < o.results.size(); ++j) Insert(o.results[j].first, std::move(o.results[j].second), o.cutoffs[j]);
      for (auto& d : o.deferred) deferred_[KeyOf(d.first, true)].push_back(std::move(d));
    }
    ordered_.erase(ordered_.begin(), ordered_.begin() + static_cast<std::ptrdiff_t>(end - base_));
    base_ = end;
    ci = end;
  }
}

}  // namespace

SearchResult search_internal::SearchOneGroup(const Mission& m, const Catalog& cat, const SearchOptions& opt,
                                             double cutoff, PropGridCache* cache,
                                             const std::vector<GroupParts>* given_parts,
                                             const std::vector<char>* pair_mask) {
  const auto t0 = std::chrono::steady_clock::now();
  if (std::string why; !opt.IsValid(&why)) throw UsageError(why);
  SearchResult out;
  SearchContext ctx;
  ctx.given_parts = given_parts;
  ctx.pair_mask = pair_mask;
  if (cache) {  // stages 0-3 with the caller's propeller grids (they depend on the air and limits only)
    ctx.mission = &m;
    ctx.catalog = &cat;
    ResolveGroups(&ctx);
    ctx.options = BatteryOptions(m, cat);
    ctx.escs = BuildEscTable(cat, ctx.options);
    if (!cache->built) BuildPropGrids(m, cat, &cache->grids, &cache->models);
    cache->built = true;
    ctx.grids = std::move(cache->grids);
    ctx.models = std::move(cache->models);
    ctx.motor_setups = &cache->motor_setups;
  } else {
    PrepareStages(m, cat, &ctx);  // stages 0-3
  }
  FixedGroupPowerBounds(&ctx);
  out.combinations = static_cast<long long>(cat.motors().size()) * static_cast<long long>(cat.escs().size()) *
                     static_cast<long long>(cat.props().size()) * static_cast<long long>(ctx.options.size());
  out.pruned_by["esc_voltage"] += ctx.escs.voltage_pruned * static_cast<long long>(cat.motors().size() * cat.props().size());
  if (ctx.escs.excluded_pruned > 0) {
    out.pruned_by["catalog_exclude"] += ctx.escs.excluded_pruned * static_cast<long long>(cat.motors().size() * cat.props().size());
  }
  {
    CandidateStream stream(ctx, opt.threads, kFirstBatch, cutoff);  // stage 4 (each motor's first batch)
    out.candidate_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    BranchAndBound bb(ctx, opt, &stream, &out, t0, cutoff);  // stage 5 (and stage 4 on demand)
    bb.Run();
    bb.ResolveDeferred();
    bb.Explain();
    stream.MergePrunedInto(&out.pruned_by);
    out.skipped_without_mass = stream.skipped_without_mass();
    out.candidate_pairs = stream.pairs_bounded();
    out.candidate_batches = stream.batches();
    out.virtual_evaluations = bb.virtual_evaluations();
  }
  if (cache) {
    cache->grids = std::move(ctx.grids);
    cache->models = std::move(ctx.models);
  }
  out.pruned = out.combinations - out.searched - out.unsettled;
  if (opt.progress && !out.interrupted) {
    SearchProgress p;
    p.fraction = 1.0;
    p.searched = out.searched;
    p.pruned = out.pruned;
    p.has_best = !out.best.empty();
    p.found = static_cast<int>(out.best.size());
    p.best_objective = p.has_best ? out.best.front().result.objective : 0.0;
    opt.progress(p);
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace dynosize
