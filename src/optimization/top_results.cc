#include "optimization/top_results.h"

#include <algorithm>

#include "rotor/family.h"

namespace dynosize::search_internal {

namespace {

std::uintptr_t Id(const void* p) { return reinterpret_cast<std::uintptr_t>(p); }

}  // namespace

EntryKey KeyOf(const Combination& c, bool distinct_designs) {
  EntryKey k;
  auto add = [&](const GroupParts& p) {
    k.push_back(Id(p.motor));
    // Designs: the sizes of one family and blade count are one design, its size a choice inside
    // it (a grid's neighbours are not alternatives to a different motor or family).
    const RotorFamily* family = distinct_designs ? FamilyOfSizedPropId(p.prop->id) : nullptr;
    k.push_back(family ? Id(family) : Id(p.prop));
    if (family) k.push_back(static_cast<std::uintptr_t>(p.prop->blades.value_or(2)));
    if (!distinct_designs) k.push_back(Id(p.esc));
  };
  if (c.groups.empty()) {
    add(GroupParts{c.motor, c.esc, c.prop});
  } else {
    for (const GroupParts& p : c.groups) add(p);
  }
  if (!distinct_designs) {
    k.push_back(Id(c.battery));
    k.push_back(static_cast<std::uintptr_t>(c.cells));
  }
  return k;
}

TopScores::TopScores(int n, bool distinct_designs, double cutoff)
    : n_(n), distinct_(distinct_designs), cutoff_(cutoff) {}

double TopScores::Threshold() const {
  return static_cast<int>(top_.size()) < n_ ? cutoff_ : std::min(cutoff_, top_[static_cast<std::size_t>(n_ - 1)].second);
}

bool TopScores::Add(const EntryKey& key, double score, EntryKey* evicted) {
  if (evicted) evicted->clear();
  if (!(score < Threshold())) return false;
  if (distinct_) {
    auto it = std::find_if(top_.begin(), top_.end(), [&](const auto& e) { return e.first == key; });
    if (it != top_.end()) {
      if (!(score < it->second)) return true;  // an alternative of a design already in
      top_.erase(it);
    }
  }
  // Ties after the entries already in (the order results came, as the merge of chunks gives it).
  auto pos = std::upper_bound(top_.begin(), top_.end(), score, [](double s, const auto& e) { return s < e.second; });
  top_.insert(pos, {key, score});
  if (static_cast<int>(top_.size()) > n_) {
    if (evicted) *evicted = std::move(top_.back().first);
    top_.pop_back();
  }
  return true;
}

TopResults::TopResults(int n, bool distinct_designs, double cutoff) : scores_(n, distinct_designs, cutoff) {}

double TopResults::best_objective() const {
  return scores_.entries().empty() ? 0.0 : best_.at(scores_.entries().front().first).best.result.objective;
}

void TopResults::TrimAlternatives(std::vector<Alternative>* a) const {
  const double t = Threshold();
  a->erase(std::remove_if(a->begin(), a->end(), [t](const Alternative& x) { return !(x.score < t); }), a->end());
  std::stable_sort(a->begin(), a->end(), [](const Alternative& x, const Alternative& y) { return x.score < y.score; });
}

void TopResults::Add(RankedCombination&& r, double solve_cutoff) {
  const EntryKey key = KeyOf(r.combination, scores_.distinct_designs());
  std::vector<Alternative> carried = std::move(r.alternatives);
  r.alternatives.clear();
  const double score = r.result.score;
  EntryKey evicted;
  if (!scores_.Add(key, score, &evicted)) return;
  // A design that left the top N takes its alternatives with it (all score at least its best).
  if (!evicted.empty()) best_.erase(evicted);
  auto it = best_.find(key);
  if (it == best_.end()) {
    Held h;
    h.best = std::move(r);
    h.best.alternatives = std::move(carried);
    h.solve_cutoff = solve_cutoff;
    best_.emplace(key, std::move(h));
    return;
  }
  Held& h = it->second;
  std::vector<Alternative>& alt = h.best.alternatives;
  alt.insert(alt.end(), carried.begin(), carried.end());
  if (score < h.best.result.score) {
    alt.push_back(Alternative{h.best.combination, h.best.result.objective, h.best.result.score, h.best.result.capacity_ah});
    std::vector<Alternative> keep = std::move(alt);
    h.best = std::move(r);
    h.best.alternatives = std::move(keep);
    h.solve_cutoff = solve_cutoff;
  } else {
    alt.push_back(Alternative{r.combination, r.result.objective, score, r.result.capacity_ah});
  }
  // Bounded memory: those at or above the threshold can never be listed (it only falls).
  if (alt.size() > 64) TrimAlternatives(&alt);
}

std::vector<RankedCombination> TopResults::Sorted(std::vector<double>* solve_cutoffs) const {
  std::vector<RankedCombination> out;
  if (solve_cutoffs) solve_cutoffs->clear();
  for (const auto& entry : scores_.entries()) {
    const Held& h = best_.at(entry.first);
    out.push_back(h.best);
    TrimAlternatives(&out.back().alternatives);
    if (solve_cutoffs) solve_cutoffs->push_back(h.solve_cutoff);
  }
  return out;
}

}  // namespace dynosize::search_internal
