// Stage 4 on demand (search_stages.h, CandidateStream): the candidate pairs in the branch and
// bound's order, each bounded only when it may be drawn next (R11, docs/search.md#r11).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <vector>

#include "optimization/motor_setup_cache.h"
#include "optimization/pair_candidates.h"

namespace dynosize::search_internal {

namespace {

// R11's keys below a cutoff (docs/search.md#r11-cutoff): per propeller, how many of the lossy
// classes (MotorClasses: ascending mass) may have a key below `cutoff` for some option. A
// class's key is at least the key with no loss floor at its own mass (the floor's terms are
// >= 0 and R4's bound rises with pdc_lb), which rises with the mass (M1, M3): a search
// over the classes finds the first whose zero-floor key reaches the cutoff (held 1e-9 above it
// against rounding); that class and every heavier one have keys at or above the cutoff for
// the propeller, which the stream never walks to. kInf cutoff: every class.
std::vector<std::size_t> KeyedClasses(const SearchContext& ctx, const MissionFacts& f,
                                      const std::vector<MotorClass>& classes, double cutoff, int threads) {
  const std::size_t n_lossy = classes.empty() ? 0 : classes.size() - 1;  // the last class is not lossy
  std::vector<std::size_t> limit(ctx.catalog->props().size(), n_lossy);
  if (!std::isfinite(cutoff)) return limit;
  const double reach = cutoff + 1e-9 * std::abs(cutoff);
  ForEachOnThreads(f.frame_ok_props.size(), threads, [&](int, std::size_t i) {
    const std::size_t pi = static_cast<std::size_t>(f.frame_ok_props[i]);
    PairLoads loads(*ctx.mission);
    std::size_t most = 0;
    for (std::size_t o = 0; o < ctx.options.size() && most < n_lossy; ++o) {
      auto reaches = [&](std::size_t c) {
        return PropOnlyBound(ctx, f, pi, o, classes[c].mass_kg, MotorLossFloor{}, &loads) >= reach;
      };
      // Galloping from `most` (the classes below it are keyed anyway): most propellers reach the
      // cutoff within a few classes of the lightest; then bisection.
      std::size_t lo = most, hi = n_lossy;
      for (std::size_t step = 1; lo < hi; step *= 2) {
        const std::size_t c = std::min(lo + step - 1, hi - 1);
        if (reaches(c)) {
          hi = c;
          break;
        }
        lo = c + 1;
      }
      while (lo < hi) {
        const std::size_t mid = lo + (hi - lo) / 2;
        if (reaches(mid)) {
          hi = mid;
        } else {
          lo = mid + 1;
        }
      }
      most = lo;
    }
    limit[pi] = most;
  });
  return limit;
}

// f with only the propellers that ctx's pair mask (motor * props + propeller) marks for at
// least one motor; f itself without a mask.
MissionFacts MaskedFacts(const SearchContext& ctx, const MissionFacts& f) {
  if (!ctx.pair_mask) return f;
  const std::size_t n_props = ctx.catalog->props().size();
  // The mask is sparse (a few pairs in a hundred): eight entries at a time are skipped while
  // they are all zero.
  std::vector<char> any(n_props, 0);
  const std::vector<char>& mask = *ctx.pair_mask;
  for (std::size_t k = 0; k < mask.size();) {
    std::uint64_t eight = 1;
    if (k + sizeof eight <= mask.size()) std::memcpy(&eight, mask.data() + k, sizeof eight);
    if (eight == 0) {
      k += sizeof eight;
      continue;
    }
    if (mask[k]) any[k % n_props] = 1;
    ++k;
  }
  MissionFacts out = f;
  out.frame_ok_props.clear();
  for (const int pi : f.frame_ok_props) {
    if (any[static_cast<std::size_t>(pi)]) out.frame_ok_props.push_back(pi);
  }
  return out;
}

}  // namespace

// Stage 4 on demand (CandidateStream). Per set-up motor: its class's keys (R11) are walked in
// order and bounded in batches; the bounded pairs wait in a heap. A motor's head is its next
// bounded pair when that pair's bound is below the key of its next unbounded one, else that
// key (a "frontier", drawn first on ties: an unbounded pair may tie with it); the motors are
// in a heap by head. Drawing a frontier bounds the motor's next batch; drawing a pair returns
// it. A pair is returned only when its bound is below every frontier, and every unbounded
// pair's bound is at least its frontier (R11: the pair's bound is the larger of R4's and its
// key), so the pairs come in CandidateBefore order, as sorting BuildCandidates would give them.
struct CandidateStream::Impl {
  struct Motor {
    const MotorSetup* setup = nullptr;  // in `setups`
    const std::vector<PropKey>* keys = nullptr;  // its class's
    std::size_t walk = 0;                        // keys before it are bounded (or skipped)
    std::vector<Candidate> pending;              // a heap: the first in CandidateBefore order on top
    std::size_t batch = 0;                       // the next batch's size
    bool Live() const { return walk < keys->size() || !pending.empty(); }
    bool HeadIsPair() const {
      return !pending.empty() && (walk == keys->size() || pending.front().bound < (*keys)[walk].bound);
    }
    double HeadBound() const { return HeadIsPair() ? pending.front().bound : (*keys)[walk].bound; }
  };
  struct BatchCounts {
    RuleCounts pruned;
    long long bounded = 0;
  };

  explicit Impl(const SearchContext& c) : ctx(c), f(StageFourFacts(c)), loads(*c.mission) {}
  // a's head comes after b's.
  bool After(std::size_t a, std::size_t b) const {
    const Motor& x = motors[a];
    const Motor& y = motors[b];
    const double bx = x.HeadBound(), by = y.HeadBound();
    if (bx != by) return by < bx;
    const bool px = x.HeadIsPair(), py = y.HeadIsPair();
    if (px != py) return px;  // a frontier first
    if (!px) return y.setup->motor < x.setup->motor;
    return CandidateBefore(y.pending.front(), x.pending.front());
  }
  // Bounds up to n more of m's pairs whose key is below the cutoff (pairs at or above it are
  // never drawn: they stay open). Returns the combinations a rule removed.
  long long Expand(Motor* m, double cutoff, std::size_t n, PairLoads* pair_loads, BatchCounts* tally) const {
    const std::vector<PropKey>& keys = *m->keys;
    auto first = [](const Candidate& a, const Candidate& b) { return CandidateBefore(b, a); };
    long long removed = 0, masked = 0;
    for (std::size_t done = 0; m->walk < keys.size() && done < n;) {
      const PropKey& k = keys[m->walk];
      if (!(k.bound < cutoff)) {
        m->walk = keys.size();
        break;
      }
      ++m->walk;
      const std::size_t o = static_cast<std::size_t>(k.option);
      if (std::isnan(m->setup->w_nl[o])) continue;  // R1 (MotorSetUp counted it)
      if (ctx.pair_mask &&
          !(*ctx.pair_mask)[static_cast<std::size_t>(m->setup->motor) * ctx.catalog->props().size() +
                            static_cast<std::size_t>(k.prop)]) {  // no score below the cutoff (G2's inner filter)
        masked += ctx.escs.rated[o];
        continue;
      }
      ++done;
      ++tally->bounded;
      Candidate c;
      if (!PairCandidate(ctx, f, *m->setup, static_cast<std::size_t>(k.prop), o, pair_loads, &c, &tally->pruned,
                         cutoff)) {
        removed += ctx.escs.rated[o];
        continue;
      }
      c.bound = std::max(c.bound, k.bound);  // R11 (-inf when it does not apply)
      if (!(c.bound < cutoff)) continue;
      m->pending.push_back(c);
      std::push_heap(m->pending.begin(), m->pending.end(), first);
    }
    if (masked > 0) tally->pruned.Add("objective_bound", masked);
    return removed + masked;
  }

  const SearchContext& ctx;
  const MissionFacts f;
  std::shared_ptr<const MotorSetupCache::Entry> setups;  // the motors' set-up (CachedMotorSetups)
  std::vector<std::vector<PropKey>> classes;
  std::vector<Motor> motors;
  std::vector<std::size_t> heap;  // live motors; the first head on top
  PairLoads loads;
  BatchCounts counts;
  long long open = 0;  // combinations of the pairs neither drawn nor removed by a stage 4 rule
  long long skipped = 0, batches = 0;
};

CandidateStream::CandidateStream(const SearchContext& ctx, int threads, std::size_t first_batch, double cutoff)
    : impl_(std::make_unique<Impl>(ctx)) {
  Impl& s = *impl_;
  s.setups = CachedMotorSetups(ctx, s.f, threads);  // reused between the joint search's inner searches
  s.setups->pruned.MergeInto(&s.counts.pruned);
  s.skipped += s.setups->skipped;
  const std::vector<std::unique_ptr<MotorSetup>>& setups = s.setups->setups;
  std::vector<MotorClass> classes;
  const std::vector<int> cls = MotorClasses(Pointers(setups), &classes);
  s.classes.resize(classes.size());
  std::vector<char> used(classes.size(), 0);
  for (std::size_t mi = 0; mi < cls.size(); ++mi) {
    if (setups[mi]) used[static_cast<std::size_t>(cls[mi])] = 1;
  }
  // Keys only for the propellers the pair mask lets through with some motor (G2's inner filter
  // lets a few in ten): a pair the mask refuses is never bounded, and left unwalked it stays
  // open, counted under objective_bound when the search ends, as when Expand skips it.
  const MissionFacts keyed_facts = MaskedFacts(ctx, s.f);
  // A class's keys for the propellers that may give one below the cutoff (KeyedClasses); the
  // others' keys are not below it, so the walk never reaches them.
  const std::vector<std::size_t> keyed = KeyedClasses(ctx, keyed_facts, classes, cutoff, threads);
  ForEachOnThreads(s.classes.size(), threads, [&](int, std::size_t c) {
    const bool lossy = c + 1 < s.classes.size();  // the last class is the one without R11
    if (!used[c]) return;
    if (!lossy || !std::isfinite(cutoff)) {
      s.classes[c] = ClassKeys(ctx, keyed_facts, classes[c], lossy);
      return;
    }
    MissionFacts fc = s.f;
    fc.frame_ok_props.clear();
    for (const int pi : keyed_facts.frame_ok_props) {
      if (keyed[static_cast<std::size_t>(pi)] > c) fc.frame_ok_props.push_back(pi);
    }
    s.classes[c] = ClassKeys(ctx, fc, classes[c], true);
  });
  const long long per_option_props = static_cast<long long>(s.f.frame_ok_props.size());
  for (std::size_t mi = 0; mi < setups.size(); ++mi) {
    if (!setups[mi]) continue;
    Impl::Motor m;
    m.keys = &s.classes[static_cast<std::size_t>(cls[mi])];
    m.batch = std::max<std::size_t>(first_batch, 1);
    for (std::size_t o = 0; o < ctx.options.size(); ++o) {
      if (!std::isnan(setups[mi]->w_nl[o])) s.open += ctx.escs.rated[o] * per_option_props;
    }
    m.setup = setups[mi].get();
    s.motors.push_back(std::move(m));
  }
  // Each motor's first batch, on the threads.
  std::vector<Impl::BatchCounts> thread_counts(static_cast<std::size_t>(std::max(1, threads)));
  std::vector<long long> thread_removed(thread_counts.size(), 0);
  ForEachOnThreads(s.motors.size(), threads, [&](int tid, std::size_t i) {
    PairLoads loads(*ctx.mission);
    thread_removed[tid] += s.Expand(&s.motors[i], cutoff, s.motors[i].batch, &loads, &thread_counts[tid]);
    s.motors[i].batch = std::min(2 * s.motors[i].batch, kMaxBatch);
  });
  for (std::size_t t = 0; t < thread_counts.size(); ++t) {
    thread_counts[t].pruned.MergeInto(&s.counts.pruned);
    s.counts.bounded += thread_counts[t].bounded;
    s.open -= thread_removed[t];
  }
  for (std::size_t i = 0; i < s.motors.size(); ++i) {
    if (s.motors[i].Live()) s.heap.push_back(i);
  }
  std::make_heap(s.heap.begin(), s.heap.end(), [&s](std::size_t a, std::size_t b) { return s.After(a, b); });
}

CandidateStream::~CandidateStream() = default;

bool CandidateStream::Next(double cutoff, Candidate* c) {
  Impl& s = *impl_;
  auto after = [&s](std::size_t a, std::size_t b) { return s.After(a, b); };
  auto first = [](const Candidate& a, const Candidate& b) { return CandidateBefore(b, a); };
  while (!s.heap.empty()) {
    std::pop_heap(s.heap.begin(), s.heap.end(), after);
    const std::size_t i = s.heap.back();
    s.heap.pop_back();
    Impl::Motor& m = s.motors[i];
    const bool pair = m.HeadIsPair();
    if (pair) {
      std::pop_heap(m.pending.begin(), m.pending.end(), first);
      *c = m.pending.back();
      m.pending.pop_back();
      s.open -= s.ctx.escs.rated[static_cast<std::size_t>(c->option)];
    } else {
      s.open -= s.Expand(&m, cutoff, m.batch, &s.loads, &s.counts);
      m.batch = std::min(2 * m.batch, kMaxBatch);
      ++s.batches;
    }
    if (m.Live()) {
      s.heap.push_back(i);
      std::push_heap(s.heap.begin(), s.heap.end(), after);
    } else {
      std::vector<Candidate>().swap(m.pending);
    }
    if (pair) return true;
  }
  return false;
}

long long CandidateStream::batches() const { return impl_->batches; }
long long CandidateStream::pairs_bounded() const { return impl_->counts.bounded; }
long long CandidateStream::open_combinations() const { return impl_->open; }
long long CandidateStream::PairsLeftBelow(double cutoff) const {
  long long n = 0;
  for (const Impl::Motor& m : impl_->motors) {
    if (!m.Live()) continue;
    n += static_cast<long long>(m.pending.size());
    // The keys from `walk` on are in ascending order (ClassKeys; all -inf when R11 does not apply).
    const auto first = m.keys->begin() + static_cast<std::ptrdiff_t>(m.walk);
    n += std::partition_point(first, m.keys->end(), [cutoff](const PropKey& k) { return k.bound < cutoff; }) - first;
  }
  return n;
}
long long CandidateStream::skipped_without_mass() const { return impl_->skipped; }
void CandidateStream::MergePrunedInto(std::map<std::string, long long>* out) const { impl_->counts.pruned.MergeInto(out); }

}  // namespace dynosize::search_internal
