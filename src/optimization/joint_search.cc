// The joint search's driver (joint_search.h; G2, G3, docs/search.md#g2): the outer pairs and
// triples best bound first, each searched with the outer group fixed; the bounds are in
// joint_bounds.cc and joint_frontier.cc.
#include "optimization/joint_search.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <map>
#include <memory>
#include <queue>
#include <set>
#include <stdexcept>
#include <tuple>
#include <utility>
#include <vector>

#include "common/error.h"
#include "common/units.h"
#include "model/physics.h"
#include "optimization/components.h"
#include "optimization/credibility.h"
#include "optimization/top_results.h"

namespace dynosize {

// The rule (G2) and its proof are in docs/search.md#g2, with R0-R12 and G1.

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

long long SaturatingProduct(std::initializer_list<long long> xs) {
  long long p = 1;
  for (long long x : xs) {
    if (__builtin_mul_overflow(p, x, &p)) return std::numeric_limits<long long>::max();
  }
  return p;
}

// x += y, held at the largest long long (counts of three or more free groups).
void AddCount(long long* x, long long y) {
  if (__builtin_add_overflow(*x, y, x)) *x = std::numeric_limits<long long>::max();
}

// Combinations of one free group per battery option: motors x ESCs x propellers.
long long GroupCombinations(const Catalog& cat) {
  return SaturatingProduct({static_cast<long long>(cat.motors().size()), static_cast<long long>(cat.escs().size()),
                            static_cast<long long>(cat.props().size())});
}


}  // namespace

int FreeGroupCount(const Mission& m) {
  if (m.groups.empty()) return 1;
  int n = 0;
  for (const PropulsionGroup& g : m.groups) n += g.fixed() ? 0 : 1;
  return n;
}

namespace search_internal {

namespace {

// Appends an inner search's results and counts to *out, its results to the top N (`top`).
void Merge(SearchResult&& r, TopResults* top, SearchResult* out) {
  out->searched += r.searched;
  for (const auto& [rule, n] : r.pruned_by) AddCount(&out->pruned_by[rule], n);
  out->evaluated_mass_objective.insert(out->evaluated_mass_objective.end(), r.evaluated_mass_objective.begin(),
                                       r.evaluated_mass_objective.end());
  out->candidate_pairs += r.candidate_pairs;
  out->candidate_seconds += r.candidate_seconds;
  out->virtual_evaluations += r.virtual_evaluations;
  out->put_back_solves += r.put_back_solves;
  out->candidate_batches += r.candidate_batches;
  AddCount(&out->unsettled, r.unsettled);
  for (RankedCombination& b : r.best) top->Add(std::move(b));
}

// Adds `results` (exact solves) to *top, leaving out the combinations it already holds as a
// result or a listed alternative (an item stopped while taken again may have found them too).
void AddUnheld(std::vector<RankedCombination>&& results, TopResults* top) {
  std::set<EntryKey> held;
  for (const RankedCombination& r : top->Sorted()) {
    held.insert(KeyOf(r.combination, false));
    for (const Alternative& a : r.alternatives) held.insert(KeyOf(a.combination, false));
  }
  for (RankedCombination& r : results) {
    if (held.count(KeyOf(r.combination, false)) > 0) continue;
    auto& alt = r.alternatives;
    alt.erase(std::remove_if(alt.begin(), alt.end(),
                             [&](const Alternative& a) { return held.count(KeyOf(a.combination, false)) > 0; }),
              alt.end());
    top->Add(std::move(r));
  }
}

struct OuterPair {
  double bound;
  int motor, prop;
  std::size_t option;
};

// The outer group's (motor, propeller, option) pairs that survive R0, R1, R3 with their bound
// (the least over ESC classes), best first; the pruned ones counted (x `block`: the inner
// combinations of each).
std::vector<OuterPair> OuterPairs(const Catalog& cat, JointBounds* jb, long long block, SearchResult* out) {
  std::vector<OuterPair> pairs;
  const long long n_esc = static_cast<long long>(cat.escs().size());
  const long long n_prop = static_cast<long long>(cat.props().size());
  for (std::size_t mi = 0; mi < cat.motors().size(); ++mi) {
    if (!cat.motors()[mi].mass_kg) ++out->skipped_without_mass;
    for (std::size_t o = 0; o < jb->options().size(); ++o) {
      if (const char* rule = jb->MotorRule(static_cast<int>(mi), o)) {
        AddCount(&out->pruned_by[rule], SaturatingProduct({n_esc, n_prop, block}));
        continue;
      }
      for (std::size_t pi = 0; pi < cat.props().size(); ++pi) {
        if (const char* rule = jb->PropRule(static_cast<int>(pi))) {
          AddCount(&out->pruned_by[rule], SaturatingProduct({n_esc, block}));
          continue;
        }
        double best = kInf, irms = 0;
        const char* why = "throttle";
        for (std::size_t c = 0; c < jb->escs().classes.size(); ++c) {
          if (jb->escs().per_option[o][c].empty()) continue;
          const char* w = nullptr;
          const double b = jb->PairBound(static_cast<int>(mi), static_cast<int>(pi), o, static_cast<int>(c), &w, &irms);
          if (b < kInf) {
            best = std::min(best, b);
          } else if (w) {
            why = w;
          }
        }
        if (!(best < kInf)) {
          AddCount(&out->pruned_by[why], SaturatingProduct({n_esc, block}));
          continue;
        }
        pairs.push_back(OuterPair{best, static_cast<int>(mi), static_cast<int>(pi), o});
      }
    }
  }
  std::sort(pairs.begin(), pairs.end(), [](const OuterPair& a, const OuterPair& b) {
    if (a.bound != b.bound) return a.bound < b.bound;
    if (a.option != b.option) return a.option < b.option;
    if (a.motor != b.motor) return a.motor < b.motor;
    return a.prop < b.prop;
  });
  return pairs;
}

// The progress of the outer loop before pair `done` (SearchProgress): the share of the work, the
// inner searches' counts so far and the best so far.
void ReportProgress(const SearchOptions& opt, const std::vector<OuterPair>& pairs, std::size_t done,
                    const TopResults& top, const SearchResult& out) {
  if (!opt.progress) return;
  SearchProgress p;
  // As the one-group search's (branch_and_bound.cc, ReportProgress): the outer pairs taken against those
  // taken plus those left below the N-th best (they are sorted by bound).
  const double t = top.Threshold();
  const auto below = std::partition_point(pairs.begin(), pairs.end(), [t](const OuterPair& x) { return x.bound < t; });
  const double left = static_cast<double>(std::max<std::ptrdiff_t>(0, (below - pairs.begin()) - static_cast<std::ptrdiff_t>(done)));
  p.fraction = left == 0 ? 1.0 : static_cast<double>(done) / (static_cast<double>(done) + left);
  p.searched = out.searched;
  // The rules' counts overlap (an ESC over its voltage rating on a pair R0 removes is counted
  // by both, as in the one-group search): held to what is not yet searched.
  for (const auto& [rule, n] : out.pruned_by) AddCount(&p.pruned, n);
  p.pruned = std::min(p.pruned, out.combinations - out.searched);
  p.has_best = !top.empty();
  p.found = top.size();
  p.best_objective = top.best_objective();
  opt.progress(p);
}

// m with the outer group fixed to (pair's motor, ESC esc, pair's propeller) and the battery to
// the pair's option.
Mission SubMission(const Mission& m, const Catalog& cat, int outer, const OuterPair& pr, int esc,
                   const JointBounds& jb) {
  Mission sub = m;
  PropulsionGroup& g = sub.groups[static_cast<std::size_t>(outer)];
  g.motor_id = cat.motors()[static_cast<std::size_t>(pr.motor)].id;
  g.esc_id = cat.escs()[static_cast<std::size_t>(esc)].id;
  g.prop_id = cat.props()[static_cast<std::size_t>(pr.prop)].id;
  const BatteryOption& bo = jb.options()[pr.option];
  sub.battery.ids = {bo.entry->id};
  sub.battery.cells_min = sub.battery.cells_max = bo.cells;
  return sub;
}

// G3's limit: a virtual-ESC search that finds this many completions below the N-th best may have
// left some out (its own threshold fell below the cutoff); the class is then searched per ESC.
constexpr int kCompletionLimit = 512;

// G3 (docs/search.md#g3) for one real ESC e of an outer pair's class: (pair, e) with each completion the
// virtual ESC's search found below the N-th best (`completions`, best first; that search's relaxed
// mission and the virtual ESC score no worse than e on the mission, M2, M3, so no other
// completion scoring below the list's end can beat the N-th best), solved exactly, best virtual
// score first, until that score reaches the N-th best; the results join *out's top N.
// R5 across the class (docs/search.md#g3): out_at[j] holds the class's ESCs whose solve with
// completion j was proven unable to beat the N-th best of its moment (at or above it, or
// infeasible as RulesOutDominatedEscs says); an ESC one of them dominates scores no better with
// it (M2, M3), against an N-th best that has only fallen since, and is not solved (counted in
// *dominated). e joins out_at where its own solves are so proven. Returns the number of solves.
template <typename NthBest>
long long SolveAgainstCompletions(const Mission& sub, const Catalog& cat, int outer, int e,
                                  const std::vector<RankedCombination>& completions,
                                  const std::vector<const PropModel*>& group_models, const PropGridCache& cache,
                                  const NthBest& nth, std::vector<std::vector<int>>* out_at, long long* dominated,
                                  TopResults* top, SearchResult* out) {
  const auto& escs = cat.escs();
  const EscEntry& esc = escs[static_cast<std::size_t>(e)];
  long long solved = 0;
  for (std::size_t j = 0; j < completions.size(); ++j) {
    const RankedCombination& done = completions[j];
    const double cutoff = nth();
    if (!(done.result.score < cutoff)) break;  // every later completion scores no better
    std::vector<int>& out_j = (*out_at)[j];
    if (std::any_of(out_j.begin(), out_j.end(), [&](int d) { return EscDominates(escs[static_cast<std::size_t>(d)], esc); })) {
      ++*dominated;
      continue;
    }
    Combination c = done.combination;
    c.groups[static_cast<std::size_t>(outer)].esc = &esc;
    const PropModel* model = cache.models[static_cast<std::size_t>(c.prop - cat.props().data())].get();
    const MissionEvaluator eval(sub, c, model, &group_models);
    MissionResult res = eval.Solve(cutoff, false, false, true);  // search: the infeasibility exits too
    ++solved;
    if (res.bounded_out) {
      out_j.push_back(e);
      continue;
    }
    ++out->searched;
    if (!res.feasible) {
      if (RulesOutDominatedEscs(res)) out_j.push_back(e);
      continue;
    }
    out->evaluated_mass_objective.emplace_back(res.propulsion_mass_kg, res.objective);
    if (!(res.score < cutoff)) {
      out_j.push_back(e);
      continue;
    }
    res = eval.Solve(cutoff);  // explained, as the inner search explains its top N (same numbers)
    top->Add(RankedCombination{c, std::move(res), {}}, cutoff);
  }
  return solved;
}

}  // namespace

namespace {

// G2's loop over the outer group's pairs and triples (docs/search.md#g2: order, R5, G3), best first from
// one queue, the inner searches merged into one top N.
class JointLoop {
 public:
  JointLoop(const Mission& m, const Catalog& cat, const SearchOptions& opt, double cutoff, PropGridCache* cache,
            JointBounds* jb, const std::vector<OuterPair>& pairs, long long block, long long first_search_budget,
            SearchResult* out)
      : m_(m), cat_(cat), opt_(opt), cache_(cache), jb_(*jb), pairs_(pairs), block_(block),
        first_search_budget_(first_search_budget),
        n_esc_(static_cast<long long>(cat.escs().size())), out_(*out), top_(opt.top_n, opt.distinct_designs, cutoff),
        put_back_(opt.top_n, opt.distinct_designs, cutoff) {
    inner_opt_ = opt;
    inner_opt_.progress = nullptr;
    // The virtual ESC only with two free groups (the inner search is the one-group search) and
    // the catalog's ESC values as the ranking flies them (ScenarioEscParams leaves them).
    virtual_ok_ = FreeGroupCount(m) == 2 && m.objective.ranking != DataScenario::kPessimistic &&
                  m.objective.ranking != DataScenario::kOptimistic;
    relaxed_ = m;
    relaxed_.constraints.min_hover_throttle = 0.0;
    relaxed_.constraints.prop_below_data_factor = 0.0;  // as min_hover_throttle (docs/search.md#r12)
  }

  // The whole loop; then out's best, N-th best and progress.
  void Run();

 private:
  // A pair (esc -1, under its coupled bound) or one ESC's inner search (under its triple bound).
  struct Queued {
    double bound;
    std::size_t pair;
    int esc;
    bool unlimited = false;  // taken before (put back): no budget now
    bool operator>(const Queued& o) const { return std::tie(bound, pair, esc) > std::tie(o.bound, o.pair, o.esc); }
  };
  // What the loop prunes against: the N-th best of the results kept, or of those found by the
  // inner searches put back, whichever is lower (G2's order, docs/search.md#g2).
  double Nth() const {
    const double t = put_back_.Threshold();
    return std::min(top_.Threshold(), t < kInf ? std::nextafter(t, kInf) : kInf);
  }
  void Progress(std::size_t done) const { ReportProgress(opt_, pairs_, done, top_, out_); }
  // The next pair of the list under its coupled bound (G2's order: the uncoupled one is lower).
  void Tighten();
  // The outer group fixed to (pair, ESC e), the battery to the pair's option: the inner search.
  // budgeted (only while there is no N-th best): an inner search that has not finished within
  // first_search_budget_ solves is put back (false) and taken again later; its results only
  // lower Nth() (put_back_) and join the top N if the search is stopped first.
  bool SearchTriple(const OuterPair& pr, int e, bool budgeted);
  // A pair's ESC classes: per class the bounds, the virtual ESC (R5, G3); the single ESCs left
  // go into the queue. False: the pair was put back (its first inner search over its budget).
  bool TakePair(const Queued& q);
  // One class with two or more ESCs below the N-th best (`cls`, best triple bound first): the
  // virtual ESC's completions, then each real ESC against them (G3) or its own inner search.
  void VirtualEscClass(const OuterPair& pr, std::size_t i, const std::vector<std::pair<double, int>>& cls,
                       int esc_class);
  // Everything left is unsettled (a stop): the item being taken has bound `bound` and `left`
  // combinations not yet settled, the rest the queue's and the list's own bounds.
  void StopAll(double bound, long long left);
  long long QueuedCombinations(const Queued& q) const { return q.esc < 0 ? SaturatingProduct({n_esc_, block_}) : block_; }

  const Mission& m_;
  const Catalog& cat_;
  const SearchOptions& opt_;
  PropGridCache* cache_;
  JointBounds& jb_;
  const std::vector<OuterPair>& pairs_;
  const long long block_, first_search_budget_, n_esc_;
  SearchResult& out_;
  TopResults top_;  // top_results.h
  // The scores of the results of inner searches put back over their budget (not kept: their
  // items are searched again), for Nth() only.
  TopScores put_back_;
  // Those results per item put back and not yet taken again (by (pair, esc)): they join the top N
  // only when the search is stopped first (StopAll); taken again, the item finds them itself.
  std::map<std::pair<std::size_t, int>, std::vector<RankedCombination>> put_back_results_;
  std::vector<RankedCombination> last_put_back_;  // SearchTriple's, for Run
  SearchOptions inner_opt_;
  bool virtual_ok_ = false;
  Mission relaxed_;
  std::priority_queue<Queued, std::vector<Queued>, std::greater<>> queue_;
  // Items whose budgeted inner search did not finish: back into the queue once an N-th best is
  // known (their bounds then prune most of them), or, when nothing else is left, unlimited.
  std::vector<Queued> deferred_;
  std::size_t next_ = 0;  // the list's next pair not yet in the queue
};

void JointLoop::Run() {
  std::size_t taken = 0;
  for (;;) {
    const bool drained = next_ == pairs_.size() && queue_.empty();
    if (!deferred_.empty() && (Nth() < kInf || drained)) {
      for (Queued d : deferred_) {
        d.unlimited = true;
        queue_.push(d);
      }
      deferred_.clear();
    }
    const bool from_list = next_ < pairs_.size() && (queue_.empty() || pairs_[next_].bound < queue_.top().bound);
    if (!from_list && queue_.empty()) break;
    const double least = from_list ? pairs_[next_].bound : queue_.top().bound;
    if (!(least < Nth())) {  // G2: every pair and triple left has a bound at least as bad
      long long left = SaturatingProduct({static_cast<long long>(pairs_.size() - next_), n_esc_, block_});
      for (; !queue_.empty(); queue_.pop()) AddCount(&left, QueuedCombinations(queue_.top()));
      AddCount(&out_.pruned_by["objective_bound"], left);
      break;
    }
    if (StopRequested(opt_)) {
      StopAll(least, 0);
      break;
    }
    if (from_list) {
      Tighten();
      continue;
    }
    const Queued q = queue_.top();
    queue_.pop();
    if (taken++ % 64 == 0) Progress(next_);
    const bool budgeted = !q.unlimited && !(Nth() < kInf);
    const bool done = q.esc >= 0 ? SearchTriple(pairs_[q.pair], q.esc, budgeted) : TakePair(q);
    if (!done) {
      deferred_.push_back(q);
      put_back_results_[{q.pair, q.esc}] = std::move(last_put_back_);
      last_put_back_.clear();
      continue;
    }
    if (!out_.interrupted) put_back_results_.erase({q.pair, q.esc});  // found again
    if (out_.interrupted) {  // stopped in this item's inner searches: the rest of it is unsettled
      StopAll(q.bound, QueuedCombinations(q));
      break;
    }
  }
  if (!out_.interrupted) Progress(pairs_.size());
  out_.best = top_.Sorted();
  out_.nth_best_score = top_.Threshold();
}

void JointLoop::Tighten() {
  const OuterPair& pr = pairs_[next_];
  double bound = kInf;
  for (std::size_t c = 0; c < jb_.escs().classes.size(); ++c) {
    if (jb_.escs().per_option[pr.option][c].empty()) continue;
    const char* why = nullptr;
    double irms_lb = 0;
    bound = std::min(bound, jb_.PairBound(pr.motor, pr.prop, pr.option, static_cast<int>(c), &why, &irms_lb));
  }
  if (bound < kInf) {
    queue_.push(Queued{std::max(bound, pr.bound), next_, -1});
  } else {
    AddCount(&out_.pruned_by["objective_bound"], SaturatingProduct({n_esc_, block_}));
  }
  ++next_;
}

bool JointLoop::SearchTriple(const OuterPair& pr, int e, bool budgeted) {
  const Mission sub = SubMission(m_, cat_, jb_.outer_group(), pr, e, jb_);
  SearchOptions o = inner_opt_;
  if (budgeted && FreeGroupCount(sub) == 1) o.evaluation_budget = first_search_budget_;
  // G2's inner filter once an N-th best is known (docs/search.md#g2-inner-filter).
  std::vector<char> allowed;
  bool filtered = false;
  if (Nth() < kInf && FreeGroupCount(sub) == 1) {
    JointBounds::OuterEnergy outer_energy;
    const char* why = nullptr;
    jb_.TripleBound(pr.motor, e, pr.prop, pr.option, &why, &outer_energy);
    filtered = jb_.InnerPairsBelow(pr.option, outer_energy, Nth(), &allowed);
  }
  const auto t0 = std::chrono::steady_clock::now();
  SearchResult r = FreeGroupCount(sub) > 1
                       ? JointSearch(sub, cat_, o, Nth(), cache_)
                       : SearchOneGroup(sub, cat_, o, Nth(), cache_, nullptr, filtered ? &allowed : nullptr);
  ++out_.joint.triple_searches;
  out_.joint.triple_searches_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (r.interrupted && !StopRequested(opt_)) {  // over its budget: taken again later
    out_.virtual_evaluations += r.searched + r.virtual_evaluations;
    out_.put_back_solves += r.searched + r.virtual_evaluations;
    for (const RankedCombination& b : r.best) put_back_.Add(KeyOf(b.combination, opt_.distinct_designs), b.result.score);
    last_put_back_ = std::move(r.best);
    return false;
  }
  const bool stopped = r.interrupted;
  const double unsettled_bound = r.unsettled_bound_score;
  Merge(std::move(r), &top_, &out_);
  if (stopped) {
    out_.interrupted = true;
    out_.unsettled_bound_score = std::min(out_.unsettled_bound_score, unsettled_bound);
  }
  return true;
}

bool JointLoop::TakePair(const Queued& q) {
  const OuterPair& pr = pairs_[q.pair];
  const bool budgeted = !q.unlimited && !(Nth() < kInf);
  std::vector<std::pair<double, int>> triples, cls;
  bool started = false;  // work done on the pair: it may no longer be put back
  for (std::size_t c = 0; c < jb_.escs().classes.size() && !out_.interrupted; ++c) {
    const std::vector<int>& members = jb_.escs().per_option[pr.option][c];
    if (members.empty()) continue;
    const char* why = "objective_bound";
    double irms_lb = 0;
    const double cb = jb_.PairBound(pr.motor, pr.prop, pr.option, static_cast<int>(c), &why, &irms_lb);
    if (!(cb < Nth())) {
      AddCount(&out_.pruned_by[cb < kInf ? "objective_bound" : why],
               SaturatingProduct({static_cast<long long>(members.size()), block_}));
      continue;
    }
    cls.clear();
    for (int e : members) {
      const char* w = "objective_bound";
      const double tb = jb_.TripleBound(pr.motor, e, pr.prop, pr.option, &w);
      if (tb < Nth()) {
        cls.emplace_back(tb, e);
      } else {
        AddCount(&out_.pruned_by[tb < kInf ? "objective_bound" : w], block_);
      }
    }
    std::sort(cls.begin(), cls.end());
    if (cls.size() >= 2 && virtual_ok_ && !(Nth() < kInf)) {
      // No N-th best yet: the best-bound ESC's own search first, so that the virtual ESC's
      // search has a cutoff (without one it would list every completion). Put back only before
      // any other work on the pair (nothing of it may be taken twice).
      if (!SearchTriple(pr, cls.front().second, budgeted && !started)) return false;
      started = true;
      cls.erase(cls.begin());
      if (out_.interrupted) break;
    }
    if (cls.size() >= 2 && virtual_ok_) {
      started = true;
      VirtualEscClass(pr, q.pair, cls, static_cast<int>(c));
      continue;
    }
    triples.insert(triples.end(), cls.begin(), cls.end());
  }
  if (!out_.interrupted) {
    for (const auto& [tb, e] : triples) queue_.push(Queued{std::max(tb, q.bound), q.pair, e});
  }
  return true;
}

void JointLoop::VirtualEscClass(const OuterPair& pr, std::size_t i, const std::vector<std::pair<double, int>>& cls,
                                int esc_class) {
  const auto& escs = cat_.escs();
  const int outer = jb_.outer_group();
  // R5 for the outer group: the class's virtual ESC (no resistance, the lightest of these ESCs'
  // mass, no current limit) scores no worse than any of them with every completion (M2, M3), on
  // the mission without min_hover_throttle (the one limit it may fail when a real ESC passes).
  // Nothing below the N-th best with it: nothing with them either.
  EscEntry virt;
  virt.id = "virtual";
  virt.params = escs[static_cast<std::size_t>(cls.front().second)].params;
  virt.params.resc_ohm = 0.0;
  virt.params.max_current_a = kInf;
  double kg = kInf;
  for (const auto& t : cls) kg = std::min(kg, EscMassKg(escs[static_cast<std::size_t>(t.second)]));
  virt.mass_kg = kg;
  std::vector<GroupParts> given(m_.groups.size());
  given[static_cast<std::size_t>(outer)] =
      GroupParts{&cat_.motors()[static_cast<std::size_t>(pr.motor)], &virt, &cat_.props()[static_cast<std::size_t>(pr.prop)]};
  Progress(i);
  // G3: every completion below the N-th best with the virtual ESC, up to kCompletionLimit.
  SearchOptions all_opt = inner_opt_;
  all_opt.top_n = kCompletionLimit;
  all_opt.distinct_designs = false;  // every completion, not one per design
  // G2's inner filter: only the inner pairs whose energy floor leaves a completion below the
  // N-th best (docs/search.md#g2-inner-filter); the virtual ESC is one of the class's (zero
  // resistance, the lightest mass), which outer_energy bounds.
  JointBounds::OuterEnergy outer_energy;
  const char* why = nullptr;
  double irms_lb = 0;
  jb_.PairBound(pr.motor, pr.prop, pr.option, esc_class, &why, &irms_lb, &outer_energy);
  std::vector<char> allowed;
  const bool filtered = jb_.InnerPairsBelow(pr.option, outer_energy, Nth(), &allowed);
  const auto t0 = std::chrono::steady_clock::now();
  const SearchResult r = SearchOneGroup(SubMission(relaxed_, cat_, outer, pr, cls.front().second, jb_), cat_,
                                        all_opt, Nth(), cache_, &given, filtered ? &allowed : nullptr);
  ++out_.joint.class_searches;
  out_.joint.class_searches_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  out_.virtual_evaluations += r.searched + r.virtual_evaluations;
  if (r.interrupted) {  // the pair is left unsettled (Run)
    out_.interrupted = true;
    return;
  }
  if (r.best.empty()) {
    AddCount(&out_.pruned_by["objective_bound"], SaturatingProduct({static_cast<long long>(cls.size()), block_}));
    return;
  }
  // Every completion not in r.best scores at least `complete_below` with the virtual ESC: while
  // the N-th best is at or below it, the list is every completion that can matter.
  const double complete_below = static_cast<int>(r.best.size()) < kCompletionLimit ? kInf : r.best.back().result.score;
  std::vector<const PropModel*> group_models(m_.groups.size(), nullptr);
  group_models[static_cast<std::size_t>(outer)] = cache_->models[static_cast<std::size_t>(pr.prop)].get();
  std::vector<std::vector<int>> out_at(r.best.size());  // SolveAgainstCompletions' R5
  for (const auto& [tb, e] : cls) {
    if (out_.interrupted || StopRequested(opt_)) {
      out_.interrupted = true;
      return;
    }
    if (!(tb < Nth())) {
      AddCount(&out_.pruned_by["objective_bound"], block_);
    } else if (Nth() <= complete_below) {
      long long dominated = 0;
      const long long solved =
          SolveAgainstCompletions(SubMission(m_, cat_, outer, pr, e, jb_), cat_, outer, e, r.best, group_models,
                                  *cache_, [this]() { return Nth(); }, &out_at, &dominated, &top_, &out_);
      AddCount(&out_.pruned_by["esc_dominated"], dominated);
      AddCount(&out_.pruned_by["objective_bound"], block_ - std::min(block_, solved + dominated));
    } else {
      SearchTriple(pr, e, false);
    }
  }
}

void JointLoop::StopAll(double bound, long long left) {
  out_.interrupted = true;
  // The results of the items put back and not taken again: exact solves, not yet in the top N.
  for (auto& entry : put_back_results_) AddUnheld(std::move(entry.second), &top_);
  put_back_results_.clear();
  double least = bound;
  if (next_ < pairs_.size()) least = std::min(least, pairs_[next_].bound);
  if (!queue_.empty()) least = std::min(least, queue_.top().bound);
  for (const Queued& d : deferred_) least = std::min(least, d.bound);
  out_.unsettled_bound_score = std::min(out_.unsettled_bound_score, least);
  AddCount(&out_.unsettled, left);
  AddCount(&out_.unsettled, SaturatingProduct({static_cast<long long>(pairs_.size() - next_), n_esc_, block_}));
  for (; !queue_.empty(); queue_.pop()) AddCount(&out_.unsettled, QueuedCombinations(queue_.top()));
  for (const Queued& d : deferred_) AddCount(&out_.unsettled, QueuedCombinations(d));
  deferred_.clear();
}

}  // namespace

SearchResult JointSearch(const Mission& m, const Catalog& cat, const SearchOptions& opt, double cutoff,
                         PropGridCache* cache, long long first_search_budget) {
  const auto t0 = std::chrono::steady_clock::now();
  if (std::string why; !opt.IsValid(&why)) throw UsageError(why);
  PropGridCache own;
  if (!cache) cache = &own;
  if (!cache->built) {
    BuildPropGrids(m, cat, &cache->grids, &cache->models);
    cache->built = true;
  }
  for (int g = 0; g < GroupCount(m); ++g) {  // a fixed id not in the catalog: the JSON path
    if (m.groups[g].fixed()) FixedGroupParts(m, cat, g);
  }
  JointBounds jb(m, cat, *cache);
  const double setup_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  SearchResult out;
  const long long per_group = GroupCombinations(cat);
  long long block = 1;  // the inner combinations of one outer choice and option
  for (int i = 1; i < FreeGroupCount(m); ++i) block = SaturatingProduct({block, per_group});
  const long long n_motor = static_cast<long long>(cat.motors().size());
  const long long n_prop = static_cast<long long>(cat.props().size());
  out.combinations = SaturatingProduct({per_group, block, static_cast<long long>(jb.options().size())});
  AddCount(&out.pruned_by["esc_voltage"], SaturatingProduct({jb.escs().voltage_pruned, n_motor, n_prop, block}));
  if (jb.escs().excluded_pruned > 0) {
    AddCount(&out.pruned_by["catalog_exclude"], SaturatingProduct({jb.escs().excluded_pruned, n_motor, n_prop, block}));
  }
  const std::vector<OuterPair> pairs = OuterPairs(cat, &jb, block, &out);
  jb.set_coupled(true);  // the tighter bound for the pairs taken (G2)
  out.candidate_pairs = static_cast<long long>(pairs.size());
  out.candidate_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  out.joint.setup_s = setup_s;
  out.joint.outer_pairs_s = out.candidate_seconds - setup_s;
  JointLoop(m, cat, opt, cutoff, cache, &jb, pairs, block, first_search_budget, &out).Run();
  if (!out.interrupted && static_cast<int>(out.best.size()) >= opt.top_n) {
    const double nth = out.best.back().result.score;
    out.joint.outer_pairs_below_final =
        std::partition_point(pairs.begin(), pairs.end(), [nth](const OuterPair& x) { return x.bound < nth; }) -
        pairs.begin();
  }
  out.pruned = out.combinations - out.searched - out.unsettled;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace search_internal
}  // namespace dynosize
