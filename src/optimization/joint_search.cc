// The joint search's driver (joint_search.h; G2, G3, docs/search.md#g2): the outer pairs and
// triples best bound first, each searched with the outer group fixed; the bounds are in
// joint_bounds.cc and joint_frontier.cc.
#include "optimization/joint_search.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
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
// combinations of each). Every motor_stride-th motor only (1: all; the dive's sample counts
// nothing). A stop (SearchOptions) between motors returns what was bounded; *stopped_at: the
// first motor not taken (the catalog's motor count when none was left).
// every_64_motors (optional): called between motors now and then (progress).
std::vector<OuterPair> OuterPairs(const Catalog& cat, JointBounds* jb, long long block, std::size_t motor_stride,
                                  const SearchOptions& opt, SearchResult* out, std::size_t* stopped_at,
                                  const std::function<void()>& every_64_motors = nullptr) {
  std::vector<OuterPair> pairs;
  SearchResult uncounted;
  if (motor_stride > 1) out = &uncounted;
  const long long n_esc = static_cast<long long>(cat.escs().size());
  const long long n_prop = static_cast<long long>(cat.props().size());
  *stopped_at = cat.motors().size();
  for (std::size_t mi = 0; mi < cat.motors().size(); mi += motor_stride) {
    if (StopRequested(opt)) {
      *stopped_at = mi;
      break;
    }
    if (every_64_motors && mi % 64 == 0) every_64_motors();
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
// least_left: the least bound of what is left (a score; +inf: none known).
void ReportProgress(const Mission& m, const SearchOptions& opt, const std::vector<OuterPair>& pairs,
                    std::size_t done, const TopResults& top, const SearchResult& out, double least_left) {
  if (!opt.progress) return;
  SearchProgress p;
  // As the one-group search's (branch_and_bound.cc, ReportProgress): the outer pairs taken against those
  // taken plus those left below the N-th best (they are sorted by bound).
  // Before the first pass has bounded the pairs (pairs empty), nothing is known of the work left.
  const double t = top.Threshold();
  const auto below = std::partition_point(pairs.begin(), pairs.end(), [t](const OuterPair& x) { return x.bound < t; });
  const double left = static_cast<double>(std::max<std::ptrdiff_t>(0, (below - pairs.begin()) - static_cast<std::ptrdiff_t>(done)));
  p.fraction = pairs.empty() ? 0.0 : left == 0 ? 1.0 : static_cast<double>(done) / (static_cast<double>(done) + left);
  p.searched = out.searched;
  // The rules' counts overlap (an ESC over its voltage rating on a pair R0 removes is counted
  // by both, as in the one-group search): held to what is not yet searched.
  for (const auto& [rule, n] : out.pruned_by) AddCount(&p.pruned, n);
  p.pruned = std::min(p.pruned, out.combinations - out.searched);
  p.has_best = !top.empty();
  p.found = top.size();
  p.best_objective = top.best_objective();
  p.has_bound = std::isfinite(least_left);
  if (p.has_bound) p.bound_objective = ObjectiveOfScore(m.objective.type, least_left);
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
  // pairs: the first pass's (filled after Dive, before Run); t0: the search's start.
  JointLoop(const Mission& m, const Catalog& cat, const SearchOptions& opt, double cutoff, PropGridCache* cache,
            JointBounds* jb, const std::vector<OuterPair>& pairs, long long block, long long first_search_budget,
            std::chrono::steady_clock::time_point t0, SearchResult* out)
      : t0_(t0), m_(m), cat_(cat), opt_(opt), cache_(cache), jb_(*jb), pairs_(pairs), block_(block),
        first_search_budget_(first_search_budget),
        n_esc_(static_cast<long long>(cat.escs().size())), out_(*out), top_(opt.top_n, opt.distinct_designs, cutoff),
        put_back_(opt.top_n, opt.distinct_designs, cutoff), dive_(opt.top_n, opt.distinct_designs, cutoff) {
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

  // A good design first (docs/joint-search.md#dive), before the first pass: every
  // kDiveMotorStride-th motor's outer pairs bounded, and the best of them, each with its
  // best-bound ESC, searched with the inner group free on a budget of kDiveBudget solves, until
  // the top N is full or kDiveTries searches are done. The results are exact solves: like those
  // of an inner search put back, they only lower Nth() and join the top N if the search is
  // stopped first (the complete search finds again each one that can be in its top N).
  void Dive();
  // The whole loop; then out's best, N-th best and progress.
  void Run();
  // out's best and N-th best from the top N (the end of Run or StoppedBeforeRun).
  void Finish() {
    out_.best = top_.Sorted();
    out_.nth_best_score = top_.Threshold();
  }
  // The progress before Run (the first pass over the outer pairs).
  void FirstPassProgress() const { Progress(0); }
  // A stop before the first pass had bounded every outer pair (motors from `motor` on not
  // taken): the dive's results are the answer, nothing is proven of the rest.
  void StoppedBeforeRun(std::size_t motor);

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
  double Nth() const { return std::min(OwnNth(), Above(dive_.Threshold())); }
  // The N-th best of the loop's own searches (the dive's left out): the loop's order (budgets,
  // the best-bound ESC's own search first) follows it as it did without a dive, so that the
  // first exact searches still set a tight threshold; the dive's only prunes.
  double OwnNth() const { return std::min(top_.Threshold(), Above(put_back_.Threshold())); }
  static double Above(double t) { return t < kInf ? std::nextafter(t, kInf) : kInf; }
  // The progress with the best known: the top N and the results not yet in it (the dive's, the
  // inner searches' put back), as a stop would return them. Public for the first pass.
  void Progress(std::size_t done) const {
    if (!opt_.progress) return;
    if (dive_results_.empty() && put_back_results_.empty()) {
      ReportProgress(m_, opt_, pairs_, done, top_, out_, LeastLeft());
      return;
    }
    TopResults shown = top_;
    AddUnheld(std::vector<RankedCombination>(dive_results_), &shown);
    for (const auto& entry : put_back_results_) AddUnheld(std::vector<RankedCombination>(entry.second), &shown);
    ReportProgress(m_, opt_, pairs_, done, shown, out_, LeastLeft());
  }
  // Progress(done) when the last report is over 0.25 s old: between items and from within the
  // inner searches (one class search can run for seconds), so that the line keeps moving.
  void ProgressNowAndThen(std::size_t done) {
    if (!opt_.progress || std::chrono::steady_clock::now() - last_report_ < std::chrono::milliseconds(250)) return;
    Progress(done);
    last_report_ = std::chrono::steady_clock::now();
  }
  // The least bound of the pairs and items not yet settled: those not yet taken and the one
  // being taken (+inf: none).
  double LeastLeft() const {
    double least = std::min(taking_bound_, next_ < pairs_.size() ? pairs_[next_].bound : kInf);
    if (!queue_.empty()) least = std::min(least, queue_.top().bound);
    for (const Queued& d : deferred_) least = std::min(least, d.bound);
    return least;
  }
  // out_.first_result_s once a feasible result is known.
  void NoteFirstResult() {
    if (!std::isfinite(out_.first_result_s) &&
        (!top_.empty() || !put_back_.entries().empty() || !dive_.entries().empty())) {
      out_.first_result_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
    }
  }
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

  const std::chrono::steady_clock::time_point t0_;
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
  std::vector<RankedCombination> dive_results_;   // Dive's: they join the top N on a stop only
  TopScores dive_;                                 // their scores, for Nth()
  std::chrono::steady_clock::time_point last_report_ = std::chrono::steady_clock::now();
  SearchOptions inner_opt_;
  bool virtual_ok_ = false;
  Mission relaxed_;
  std::priority_queue<Queued, std::vector<Queued>, std::greater<>> queue_;
  // Items whose budgeted inner search did not finish: back into the queue once an N-th best is
  // known (their bounds then prune most of them), or, when nothing else is left, unlimited.
  std::vector<Queued> deferred_;
  std::size_t next_ = 0;  // the list's next pair not yet in the queue
  double taking_bound_ = kInf;  // the bound of the item being taken (+inf: none)
};

// The dive's sample, tries and budget (docs/joint-search.md#dive: how they were chosen).
constexpr std::size_t kDiveMotorStride = 16;
constexpr int kDiveTries = 8;
constexpr long long kDiveBudget = 800;
constexpr std::chrono::milliseconds kDiveTryTime{300};

// The dive's first guess of the continuous variables: m with a capacity range at its geometric
// mean and each free cruise airspeed at its middle (each search then costs plain solves, no
// continuous solve); false (and *guess m itself) when m has none.
bool DiveGuess(const Mission& m, Mission* guess) {
  *guess = m;
  bool guessed = false;
  if (guess->battery.capacity_ah && guess->battery.capacity_ah->free()) {
    const double c = std::sqrt(guess->battery.capacity_ah->lo * guess->battery.capacity_ah->hi);
    guess->battery.capacity_ah = Range{c, c};
    guessed = true;
  }
  for (Segment& sg : guess->segments) {
    if (sg.type == SegmentType::kCruise && sg.airspeed_m_s.free()) {
      const double v = 0.5 * (sg.airspeed_m_s.lo + sg.airspeed_m_s.hi);
      sg.airspeed_m_s = Range{v, v};
      guessed = true;
    }
  }
  return guessed;
}

void JointLoop::Dive() {
  const auto t0 = std::chrono::steady_clock::now();
  std::size_t stopped_at = 0;
  const std::vector<OuterPair> sample = OuterPairs(cat_, &jb_, block_, kDiveMotorStride, opt_, &out_, &stopped_at);
  const int outer = jb_.outer_group();
  Mission guess;
  const bool guessed = DiveGuess(m_, &guess);
  int tries = 0;
  std::set<int> props_tried;
  for (const OuterPair& pr : sample) {
    if (tries == kDiveTries || dive_.Threshold() < kInf || StopRequested(opt_)) break;
    // One try per propeller: where the bound ties, the propeller sets it (momentum theory at the
    // lightest vehicle), and a propeller the mission refuses refuses it with every motor.
    if (!props_tried.insert(pr.prop).second) continue;
    // The pair's ESC with the least triple bound (the one a search of the pair would take first).
    double best = kInf;
    int esc = -1;
    for (const std::vector<int>& members : jb_.escs().per_option[pr.option]) {
      for (int e : members) {
        const char* why = nullptr;
        const double b = jb_.TripleBound(pr.motor, e, pr.prop, pr.option, &why);
        if (b < best) {
          best = b;
          esc = e;
        }
      }
    }
    if (esc < 0) continue;
    ++tries;
    SearchOptions o = inner_opt_;
    o.evaluation_budget = kDiveBudget;
    // A try that bounds pairs for long without a solve (an outer choice no inner pair completes,
    // refused pair by pair) is cut off by time too.
    o.deadline = std::min(opt_.deadline, std::chrono::steady_clock::now() + kDiveTryTime);
    const Mission sub = SubMission(m_, cat_, outer, pr, esc, jb_);
    SearchResult r = guessed ? SearchOneGroup(SubMission(guess, cat_, outer, pr, esc, jb_), cat_, o, kInf, cache_)
                             : SearchOneGroup(sub, cat_, o, Nth(), cache_);
    ++out_.joint.dive_searches;
    out_.joint.dive_solves += r.searched + r.virtual_evaluations;
    std::vector<const PropModel*> group_models(m_.groups.size(), nullptr);
    group_models[static_cast<std::size_t>(outer)] = cache_->models[static_cast<std::size_t>(pr.prop)].get();
    for (RankedCombination& b : r.best) {
      if (guessed) {  // the guess's design solved exactly on the mission itself
        const PropModel* model = cache_->models[static_cast<std::size_t>(b.combination.prop - cat_.props().data())].get();
        b.result = MissionEvaluator(sub, b.combination, model, &group_models).Solve();
        b.alternatives.clear();
        ++out_.joint.dive_solves;
        if (!b.result.feasible) continue;
      }
      dive_.Add(KeyOf(b.combination, opt_.distinct_designs), b.result.score);
      dive_results_.push_back(std::move(b));
    }
    NoteFirstResult();
  }
  out_.joint.dive_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  Progress(0);  // the dive's best, before the first pass
}

void JointLoop::StoppedBeforeRun(std::size_t motor) {
  out_.interrupted = true;
  AddUnheld(std::move(dive_results_), &top_);
  dive_results_.clear();
  out_.unsettled_bound_score = -kInf;  // the pairs not yet bounded have no bound
  // The pairs bounded and those of the motors not taken.
  const long long n_motors_left = static_cast<long long>(cat_.motors().size() - motor);
  out_.unsettled = SaturatingProduct({static_cast<long long>(pairs_.size()), n_esc_, block_});
  AddCount(&out_.unsettled, SaturatingProduct({n_motors_left, static_cast<long long>(jb_.options().size()),
                                               static_cast<long long>(cat_.props().size()), n_esc_, block_}));
  out_.unsettled = std::min(out_.unsettled, out_.combinations);
  Finish();
}

void JointLoop::Run() {
  std::size_t taken = 0;
  for (;;) {
    const bool drained = next_ == pairs_.size() && queue_.empty();
    if (!deferred_.empty() && (OwnNth() < kInf || drained)) {
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
    taking_bound_ = q.bound;
    // Every 64 items, and at least every 0.25 s (an inner search can take a second).
    if (taken++ % 64 == 0) {
      Progress(next_);
      last_report_ = std::chrono::steady_clock::now();
    } else {
      ProgressNowAndThen(next_);
    }
    const bool budgeted = !q.unlimited && !(OwnNth() < kInf);
    const bool done = q.esc >= 0 ? SearchTriple(pairs_[q.pair], q.esc, budgeted) : TakePair(q);
    taking_bound_ = kInf;  // settled, put back (deferred_ holds it) or stopped (StopAll below)
    NoteFirstResult();
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
  Finish();
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
  if (opt_.progress) o.progress = [this](const SearchProgress&) { ProgressNowAndThen(next_); };
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
  const bool budgeted = !q.unlimited && !(OwnNth() < kInf);
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
    if (cls.size() >= 2 && virtual_ok_ && !(OwnNth() < kInf)) {
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
  if (opt_.progress) all_opt.progress = [this, i](const SearchProgress&) { ProgressNowAndThen(i); };
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
  AddUnheld(std::move(dive_results_), &top_);
  dive_results_.clear();
  const double least = std::min(bound, LeastLeft());
  out_.unsettled_bound_score = std::min(out_.unsettled_bound_score, least);
  AddCount(&out_.unsettled, left);
  AddCount(&out_.unsettled, SaturatingProduct({static_cast<long long>(pairs_.size() - next_), n_esc_, block_}));
  for (; !queue_.empty(); queue_.pop()) AddCount(&out_.unsettled, QueuedCombinations(queue_.top()));
  for (const Queued& d : deferred_) AddCount(&out_.unsettled, QueuedCombinations(d));
  deferred_.clear();
}

}  // namespace

SearchResult JointSearch(const Mission& m, const Catalog& cat, const SearchOptions& opt, double cutoff,
                         PropGridCache* cache, long long first_search_budget, bool dive) {
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
  std::vector<OuterPair> pairs;
  JointLoop loop(m, cat, opt, cutoff, cache, &jb, pairs, block, first_search_budget, t0, &out);
  // The dive: only in the outermost search (an inner joint search has its caller's cutoff).
  if (dive && FreeGroupCount(m) == 2 && !std::isfinite(cutoff)) {
    loop.Dive();
  }
  const auto pass_t0 = std::chrono::steady_clock::now();
  std::size_t stopped_at = 0;
  pairs = OuterPairs(cat, &jb, block, 1, opt, &out, &stopped_at, [&loop]() { loop.FirstPassProgress(); });
  jb.set_coupled(true);  // the tighter bound for the pairs taken (G2)
  out.candidate_pairs = static_cast<long long>(pairs.size());
  out.candidate_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  out.joint.setup_s = setup_s;
  out.joint.outer_pairs_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - pass_t0).count();
  if (stopped_at < cat.motors().size()) {
    loop.StoppedBeforeRun(stopped_at);
  } else {
    loop.Run();
  }
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
