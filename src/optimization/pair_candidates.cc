// Stage 4 of the catalog search (pair_candidates.h): the motors set up, each pair refused by a
// rule or bounded (R3, R4), and R11's keys (docs/search.md).
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "common/numbers.h"
#include "optimization/components.h"
#include "optimization/credibility.h"
#include "optimization/pair_candidates.h"

namespace dynosize::search_internal {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Rule R0 (docs/search.md#r0): a motor the catalog excludes is refused whole.
// R0 (the catalog excludes the motor: catalog.h, "exclude") and a motor without a mass, counted for
// all of the motor's pairs; true when the motor is skipped.
bool SkipMotor(const MotorEntry& m, long long per_motor, RuleCounts* pruned, long long* skipped) {
  if (!m.exclude_reason.empty()) {
    pruned->Add("catalog_exclude", per_motor);
    return true;
  }
  if (!m.mass_kg) {
    ++*skipped;
    pruned->Add("motor_without_mass", per_motor);
    return true;
  }
  return false;
}

// Sets up motor mi (not skipped by SkipMotor) and counts the motor-level rules: the whole
// motor (motor_unrated), an option (motor_voltage, R1), a propeller (R0, StageFourFacts) for
// every option the motor can take. False when the motor is refused whole.
bool MotorSetUp(const SearchContext& ctx, const MissionFacts& f, std::size_t mi, MotorSetup* s, RuleCounts* pruned) {
  const Mission& m = *ctx.mission;
  const MotorEntry& mo = ctx.catalog->motors()[mi];
  // credibility.h: the scenario's ratings (estimated from the mass when no source states them),
  // as the evaluator flies them; an unrated motor the mission excludes is refused (R0).
  bool unrated_excluded = false;
  s->motor = static_cast<int>(mi);
  s->mass_kg = *mo.mass_kg;
  s->mp = ScenarioMotorParams(mo, m, nullptr, &unrated_excluded);
  if (f.free_lifts && unrated_excluded) {
    pruned->Add("motor_unrated", CombinationsPerMotor(ctx));
    return false;
  }
  const double motor_max_v = f.free_lifts ? MotorMaxVoltageV(mo) : kInf;
  s->ideal.clear();
  s->lossy = true;
  for (const EscClass& c : ctx.escs.classes) {
    s->ideal.emplace_back(s->mp, ZeroResistanceEsc(c));
    s->lossy = s->lossy && DriveIsLossy(s->mp, c.c1, c.c0);
  }
  s->loss = s->lossy ? LossFloorOf(s->mp) : MotorLossFloor{};
  const long long n_props = static_cast<long long>(ctx.catalog->props().size());
  s->w_nl.assign(ctx.options.size(), kNaN);
  for (std::size_t o = 0; o < ctx.options.size(); ++o) {
    const BatteryOption& bo = ctx.options[o];
    const long long per_pair = ctx.escs.rated[o];
    if (bo.v_full > motor_max_v) {  // R1 for the motor's cells_max (credibility.h)
      pruned->Add("motor_voltage", per_pair * n_props);
      continue;
    }
    double w = 0;
    for (const Drive& d : s->ideal) w = std::max(w, d.NoLoadSpeed(bo.v_full, 1.0));
    s->w_nl[o] = w;
    for (const auto& [rule, props] : f.prop_frame_counts) pruned->Add(rule, per_pair * props);  // R0
  }
  return true;
}

// R11 (stage 4's order: a key that bounds every pair of a class of motors, docs/search.md#r11).
// The factor keeps the key a bound under rounding (the floor and the evaluator's powers are
// each within a few ulps).
constexpr double kKeyRoundingAllowance = 1.0 - 1e-9;
// The classes: a class runs from its lightest motor up to this factor times that mass
// (exclusive); its key uses that mass and its members' least loss floors. The ratio: the
// measurements that chose it are in docs/search.md#constants.
constexpr double kMotorClassMassRatio = 1.1;

}  // namespace

// A motor's combinations with the ESCs that pass R0 and R1 (what a motor-level rule removes).
long long CombinationsPerMotor(const SearchContext& ctx) {
  long long n = 0;
  for (const long long r : ctx.escs.rated) n += r;
  return n * static_cast<long long>(ctx.catalog->props().size());
}

namespace {

// R3 at one vehicle mass (the mass of `loads`) for every ESC class of option o: the least
// per-rotor hover PDC bound of the classes that pass, per DriveIsLossy (has[k] false when no
// class of that kind passes), the least Irms bound over them; the rule of the last class
// refused in *why. R4's bound is nondecreasing in pdc_lb for a given DriveIsLossy (every term
// is, and so is each correctly rounded operation): the least over the classes is the bound at
// the least pdc_lb of each kind (ScoreLowerBound reads the class only through DriveIsLossy).
struct ClassPowers {
  double pdc_min[2] = {kInf, kInf};  // [DriveIsLossy]
  bool has[2] = {false, false};
  double irms_lb = kInf;
  const char* why = "throttle";
  bool Any() const { return has[0] || has[1]; }
};
ClassPowers HoverPowersOfClasses(const SearchContext& ctx, const MotorSetup& s, std::size_t o, double omega_lb,
                                 double q_lb) {
  const MissionConstraints& k = ctx.mission->constraints;
  const double margin = 1.0 - k.current_margin;
  const BatteryOption& bo = ctx.options[o];
  const MotorParams& mp = s.mp;
  const std::vector<EscClass>& classes = ctx.escs.classes;
  ClassPowers out;
  for (std::size_t ci = 0; ci < classes.size(); ++ci) {
    if (ctx.escs.per_option[o][ci].empty()) continue;
    const Drive& d = s.ideal[ci];
    const Drive::InverseCurrents hi_v = d.InverseLight(bo.v_full, q_lb, omega_lb);
    const double t_max = ThrottleLimit(k, classes[ci].tr_sat);
    if (hi_v.throttle > t_max) { out.why = "throttle"; continue; }
    if (hi_v.irms_a > mp.max_current_a * margin) { out.why = "motor_current"; continue; }
    if (k.enforce_motor_power && d.InverseAcPower(bo.v_full, hi_v, q_lb, omega_lb) > mp.max_power_w) {
      out.why = "motor_power";
      continue;
    }
    const double pdc_lo_v = bo.v_cut * d.InverseLight(bo.v_cut, q_lb, omega_lb).idc_a;  // (59), as Inverse
    const double pdc_lb = std::max(0.0, std::min(bo.v_full * hi_v.idc_a, pdc_lo_v));  // (59), as Inverse
    const int lossy = DriveIsLossy(mp, classes[ci].c1, classes[ci].c0) ? 1 : 0;
    if (!out.has[lossy] || pdc_lb < out.pdc_min[lossy]) {
      out.has[lossy] = true;
      out.pdc_min[lossy] = pdc_lb;
    }
    out.irms_lb = std::min(out.irms_lb, hi_v.irms_a);
  }
  return out;
}

// R4's terms (ScoreLowerBoundTerms) at the mass of `loads` for each kind of class that passes
// (ClassPowers), and the bound with a budget: the least over the kinds.
struct KindTerms {
  ScoreBoundTerms terms[2];  // [DriveIsLossy]
  bool has[2] = {false, false};
  double At(double budget_ah) const {
    double bound = kInf;
    for (int lossy = 0; lossy < 2; ++lossy) {
      if (has[lossy]) bound = std::min(bound, terms[lossy].At(budget_ah));
    }
    return bound;
  }
};
// keep_floors: the other segments' terms kept in loads->floors (SegmentEnergyFloor, R13).
KindTerms TermsOfPowers(const SearchContext& ctx, const MissionFacts& f, const ClassPowers& p, std::size_t pi,
                        std::size_t o, PairLoads* loads, bool stretch_only = false, bool keep_floors = false) {
  const PropEntry& prop = ctx.catalog->props()[pi];
  KindTerms out;
  for (int lossy = 0; lossy < 2; ++lossy) {
    out.has[lossy] = p.has[lossy];
    if (p.has[lossy]) {
      out.terms[lossy] = ScoreLowerBoundTerms(ctx, f, lossy == 1, prop, *ctx.models[pi], o, loads, p.pdc_min[lossy],
                                              stretch_only, keep_floors ? &loads->floors[lossy] : nullptr);
    }
  }
  return out;
}

// R13: the other segments' energy of a heavier piece from below, per kind: from the first piece's
// terms (loads->floors, when kept) with that kind's PDC bound pdc_lb_w[kind]
// (OtherEnergyAtLeastJ), else the first piece's energy (a lighter vehicle's, M3), or 0 (which
// energy is not below) for a kind the first piece lacks.
struct OtherEnergyFloor {
  const KindTerms* first = nullptr;
  const PairLoads* loads = nullptr;  // null: no floors kept
  double avionics_w = 0;
  double At(int lossy, double pdc_lb_w) const {
    if (!first->has[lossy]) return 0.0;
    if (!loads) return first->terms[lossy].e_other_j;
    return OtherEnergyAtLeastJ(loads->floors[lossy], pdc_lb_w, avionics_w);
  }
};

// R13's piece bound from below with its own R3 (p) and the first piece's terms: per kind of
// class the piece has, the first piece's stretch power raised to the drive's term at the piece's
// PDC (StretchPowerAtLeastW) and the other segments' energy from below (OtherEnergyFloor); -inf
// when the first piece lacks a kind the piece has. At most the piece's bound.
double OwnPdcBound(const KindTerms& first, const ClassPowers& p, const OtherEnergyFloor& e, double budget_ah) {
  double bound = kInf;
  for (int lossy = 0; lossy < 2; ++lossy) {
    if (!p.has[lossy]) continue;
    if (!first.has[lossy]) return -kInf;
    ScoreBoundTerms t = first.terms[lossy];
    t.p_stretch_w = t.StretchPowerAtLeastW(p.pdc_min[lossy], e.avionics_w);
    t.e_other_j = e.At(lossy, p.pdc_min[lossy]);
    bound = std::min(bound, t.At(budget_ah));
  }
  return bound;
}

// R13's heavier pieces from the first piece's drive (docs/search.md#r13, "a heavier piece's
// drive from the first's"). For a drive without extensions (Drive::extended) and a
// zero-resistance ESC (eqs 42, 48, 57): I = Q/KT + Io and U = Rm*I + KE*omega, the same for
// every ESC class, and a class's DC current at VDC is (C1*x + C0)*I with x = U/(kv*VDC) its
// effective throttle. At a grid point (omega, Q) >= (omega_0, Q_0), with r_I = I/I_0 >= 1,
// r_U = U/U_0 >= 1 and kappa >= C0/C1 for every class (C1 > 0, C0 >= 0):
// (C1*x + C0) >= (C1*x_0 + C0)*(1 + (r_U - 1)*x_0/(x_0 + kappa)), and x_0/(x_0 + kappa) is
// least at the full-charge voltage (x_0 smallest). So each class's PDC at both voltages, hence
// R3's least PDC over the classes (classes refused at the lighter vehicle stay refused, M2),
// is at least Factor() times the first piece's (held 1e-9 below against rounding).
struct PdcGrowth {
  bool ok = false;
  double i0_a = 0, u0_v = 0, share = 0;  // share = x_0/(x_0 + kappa)
  double Factor(const MotorParams& mp, double omega_rad_s, double q_nm) const {
    const double i_a = q_nm / mp.kt_nm_per_a + mp.io_a;                          // (42)
    const double u_v = mp.rm_ohm * i_a + mp.ke_v_s_per_rad * omega_rad_s;       // (48)
    return (1.0 - 1e-9) * (i_a / i0_a) * (1.0 + (u_v / u0_v - 1.0) * share);  // (57)
  }
};
PdcGrowth PdcGrowthOf(const SearchContext& ctx, const MotorSetup& s, std::size_t o, double omega_lb, double q_lb) {
  PdcGrowth g;
  const MotorParams& mp = s.mp;
  const std::vector<EscClass>& classes = ctx.escs.classes;
  if (s.ideal.size() != classes.size() || classes.empty() || !(mp.kt_nm_per_a > 0) || !(mp.rm_ohm >= 0) ||
      !(mp.ke_v_s_per_rad > 0)) {
    return g;
  }
  double kappa = 0;
  for (std::size_t ci = 0; ci < classes.size(); ++ci) {
    if (s.ideal[ci].extended() || !(classes[ci].c1 > 0) || !(classes[ci].c0 >= 0)) return g;
    kappa = std::max(kappa, classes[ci].c0 / classes[ci].c1);
  }
  g.i0_a = q_lb / mp.kt_nm_per_a + mp.io_a;
  g.u0_v = mp.rm_ohm * g.i0_a + mp.ke_v_s_per_rad * omega_lb;
  const Drive& d = s.ideal[0];
  const double x0 = d.EffectiveThrottle(d.InverseLight(ctx.options[o].v_full, q_lb, omega_lb).throttle);
  if (!(g.i0_a > 0) || !(g.u0_v > 0) || !(x0 > 0)) return g;
  g.share = x0 / (x0 + kappa);
  g.ok = true;
  return g;
}

// The first piece's terms with each kind's stretch power raised to the drive's term at
// `factor` times its PDC (PdcGrowth): a lower bound of a heavier piece's bound when every
// kind of class the motor has passes R3 at the first piece.
double GrownStretchBound(KindTerms first, const ClassPowers& lightest, double factor, const OtherEnergyFloor& e,
                         double budget_ah) {
  for (int lossy = 0; lossy < 2; ++lossy) {
    if (!first.has[lossy]) continue;
    ScoreBoundTerms& t = first.terms[lossy];
    const double pdc_lb_w = factor * lightest.pdc_min[lossy];
    t.p_stretch_w = t.StretchPowerAtLeastW(pdc_lb_w, e.avionics_w);
    t.e_other_j = e.At(lossy, pdc_lb_w);
  }
  return first.At(budget_ah);
}

// True when every kind (DriveIsLossy) of the option's ESC classes passes R3 in `p`.
bool EveryKindPasses(const SearchContext& ctx, const MotorSetup& s, std::size_t o, const ClassPowers& p) {
  for (std::size_t ci = 0; ci < ctx.escs.classes.size(); ++ci) {
    if (ctx.escs.per_option[o][ci].empty()) continue;
    if (!p.has[DriveIsLossy(s.mp, ctx.escs.classes[ci].c1, ctx.escs.classes[ci].c0) ? 1 : 0]) return false;
  }
  return true;
}

// The lightest vehicle of pair (s, pi) with option o's pack at capacity_ah of its range (R13's
// pieces, R15): its lightest ESC, at least floor_kg (R12's and the fixed groups' floors).
double PairVehicleKg(const SearchContext& ctx, const MotorSetup& s, std::size_t pi, std::size_t o, double capacity_ah,
                     double floor_kg) {
  return std::max(VehicleMassKg(ctx, PackMassLowerBoundKg(ctx.options[o], capacity_ah), s.mass_kg,
                                ctx.grids[pi].mass_kg, ctx.escs.min_mass_kg[o]),
                  floor_kg);
}

// R15 for one pair (RaisedByNeededCapacity): its R4 bound `bound` at its lightest vehicle raised,
// with R3 at each heavier vehicle; kInf with *why when R3 refuses every class there or no pack
// of the range holds the energy. *irms_lb: raised to R3's Irms at the last vehicle.
double CapacityCoupledBound(const SearchContext& ctx, const MissionFacts& f, const MotorSetup& s, std::size_t pi,
                            std::size_t o, double floor_kg, int first_idx, double bound, double cutoff,
                            PairLoads* loads, double* irms_lb, const char** why) {
  const BatteryOption& bo = ctx.options[o];
  int idx = first_idx;  // the raw grid index of the last vehicle: each is heavier than the one before
  bool over_range = false;
  const double raised = RaisedByNeededCapacity(*ctx.mission, bo, bound, cutoff, &over_range, [&](double capacity_ah) {
    loads->Reset(PairVehicleKg(ctx, s, pi, o, capacity_ah, floor_kg));
    double w = 0, q = 0;
    HoverGridPointInBracket(f, ctx.grids[pi], loads, &idx, kGrid - 1, &w, &q);
    const ClassPowers p = HoverPowersOfClasses(ctx, s, o, w, q);
    if (!p.Any()) {
      *why = p.why;
      return kInf;
    }
    *irms_lb = std::max(*irms_lb, p.irms_lb);
    return TermsOfPowers(ctx, f, p, pi, o, loads).At(bo.capacity_hi_ah);
  });
  if (over_range) *why = "reserve_soc";
  return raised;
}

// R13's least piece refined below the cutoff (docs/search.md#r13, "the least piece refined"):
// pieces [C_j, C_j+1] with piece_lb[j] a bound of each one's scores (its own assembly's, or the
// test that passed it over, at most that). While the least is below the cutoff, that piece is
// assembled at its own mass when it was not, else split at the geometric mean: the left half
// keeps its vehicle with the budget of its new top, the right half keeps the whole's bound (a
// bound of each of its parts) until its own assembly. Every piece's bound stays a bound of its
// scores (R13 holds on any [C_a, C_b]), so the least over them is the pair's bound, at least the
// fixed pieces'. It stops at the cutoff, after kRefineSteps, or when the least piece's vehicle
// with the budget of its own lowest capacity is below the cutoff: its leftmost part keeps that
// vehicle with a budget of at least C_a, so no split can lift it (BudgetScore).
double RefineLeastPiece(const SearchContext& ctx, const MissionFacts& f, const MotorSetup& s, std::size_t pi,
                        std::size_t o, double floor_kg, int first_idx, const std::vector<double>& edges,
                        const double* piece_lb, double cutoff, PairLoads* loads) {
  constexpr int kRefineSteps = 16;
  struct Piece {
    double a_ah, b_ah, bound;
    bool own;
    KindTerms terms;
  };
  std::array<Piece, kCapacityPieces + kRefineSteps> pieces;
  std::size_t n = 0;
  for (std::size_t j = 0; j + 1 < edges.size(); ++j) {
    pieces[n++] = Piece{edges[j], edges[j + 1], piece_lb[j], false, {}};
  }
  for (int step = 0; step < kRefineSteps; ++step) {
    Piece* least = std::min_element(pieces.begin(), pieces.begin() + static_cast<std::ptrdiff_t>(n),
                                    [](const Piece& x, const Piece& y) { return x.bound < y.bound; });
    if (!(least->bound < cutoff)) break;
    if (!least->own) {
      ++loads->pieces_refined;
      loads->Reset(PairVehicleKg(ctx, s, pi, o, least->a_ah, floor_kg));
      double w = 0, q = 0;
      int idx = first_idx;
      HoverGridPointInBracket(f, ctx.grids[pi], loads, &idx, kGrid - 1, &w, &q);
      const ClassPowers p = HoverPowersOfClasses(ctx, s, o, w, q);
      if (!p.Any()) {  // R3 refuses every class at the piece's lightest vehicle: no feasible point
        least->bound = kInf;
        continue;
      }
      least->terms = TermsOfPowers(ctx, f, p, pi, o, loads);
      least->own = true;
      least->bound = std::max(least->bound, least->terms.At(least->b_ah));
      continue;
    }
    const double mid = std::sqrt(least->a_ah * least->b_ah);
    if (n == pieces.size() || !(least->terms.At(least->a_ah) >= cutoff) || !(mid > least->a_ah && mid < least->b_ah)) {
      break;
    }
    ++loads->pieces_refined;
    pieces[n++] = Piece{mid, least->b_ah, least->bound, false, {}};
    least->b_ah = mid;
    least->bound = std::max(least->bound, least->terms.At(mid));
  }
  double bound = kInf;
  for (std::size_t j = 0; j < n; ++j) bound = std::min(bound, pieces[j].bound);
  return bound;
}

}  // namespace

// Stage 4 for one pair of a set-up motor whose option R1 lets through and whose propeller
// passed R0: false with its rule counted (its option's ESCs), or true with *c (R4's bound).
bool PairCandidate(const SearchContext& ctx, const MissionFacts& f, const MotorSetup& s, std::size_t pi, std::size_t o,
                   PairLoads* loads, Candidate* c, RuleCounts* pruned, double cutoff) {
  const BatteryOption& bo = ctx.options[o];
  const long long per_pair = ctx.escs.rated[o];
  // The fixed groups' mass floor (R7, R6): a pair whose heaviest combination is below it.
  if (const char* rule = FixedMassFloorRule(ctx, o, s.mass_kg, ctx.grids[pi].mass_kg, ctx.escs.max_mass_kg[o])) {
    pruned->Add(rule, per_pair);
    return false;
  }
  // Their mass ceiling (R2, R12's top, R3 over a free cruise): a pair whose lightest combination
  // is at or above it.
  if (const char* rule = FixedMassCeilingRule(ctx, o, s.mass_kg, ctx.grids[pi].mass_kg, ctx.escs.min_mass_kg[o])) {
    pruned->Add(rule, per_pair);
    return false;
  }
  // R12's floor and the fixed groups'.
  const double floor_kg = std::max(WindowMassFloorKg(ctx, f, static_cast<int>(pi)), FixedMassFloorKg(ctx, o));
  const double mass_lb =
      std::max(VehicleMassKg(ctx, bo.mass_lo_kg, s.mass_kg, ctx.grids[pi].mass_kg, ctx.escs.min_mass_kg[o]), floor_kg);
  double omega_lb = 0, q_lb = 0;
  int first_idx = -1;  // the first piece's raw grid index (HoverGridPointInBracket)
  loads->Reset(mass_lb);
  if (const char* rule = PropRule(ctx, f, s.mass_kg, s.w_nl[o], pi, o, loads, &omega_lb, &q_lb, &first_idx)) {
    pruned->Add(rule, per_pair);
    return false;
  }
  // Rule R3 (docs/search.md#r3): throttle, Irms and PAC from below with a zero-resistance ESC
  // at the full-charge voltage (M2); above a limit no ESC and no capacity can fix it.
  // R3 and R4 over the ESC classes: the pair survives if any class can.
  const ClassPowers lightest = HoverPowersOfClasses(ctx, s, o, omega_lb, q_lb);
  if (!lightest.Any()) {
    pruned->Add(lightest.why, per_pair);
    return false;
  }
  // Rule R13 (docs/search.md#r13): over a capacity range the budget piece by piece (each piece's
  // bound is at least R4's over the whole range, which is then not needed); a piece where R3
  // refuses every class holds no feasible point (its mass is a lower bound, M2, M3).
  std::vector<double> scratch;
  const std::vector<double>& edges = PieceEdges(ctx, f, o, &scratch);
  // The first piece: its stretch power alone first (the other segments' energy 0, which theirs is
  // not below); assembled only when that is below the cutoff.
  KindTerms first = TermsOfPowers(ctx, f, lightest, pi, o, loads, !edges.empty());
  double bound = kInf;
  const double avionics_w = ctx.mission->vehicle.avionics_power_w;
  OtherEnergyFloor e_floor{&first, nullptr, avionics_w};
  // R13's bound of each piece as far as it is known (RefineLeastPiece reads it).
  double piece_lb[kCapacityPieces];
  if (edges.empty() || f.every_capacity_piece || !(first.At(edges[1]) >= cutoff)) {
    if (!edges.empty()) {
      first = TermsOfPowers(ctx, f, lightest, pi, o, loads, false, true);
      e_floor.loads = loads;
    }
    bound = first.At(edges.empty() ? bo.capacity_hi_ah : edges[1]);
    piece_lb[0] = bound;
  } else {
    piece_lb[0] = first.At(edges[1]);
    ++loads->pieces_skipped;
  }
  // The other pieces, heaviest first: a piece is assembled at its own mass only when the first
  // piece's terms with its budget (a bound of it at a lighter mass, M3), then with the stretch
  // power its grid point gives the first piece's drive (PdcGrowth), then its own stretch
  // power with them, are below both the least so far and the cutoff (docs/search.md#r13,
  // "assembled only while it can be the least").
  const PdcGrowth growth = edges.size() < 3 || f.every_capacity_piece || !EveryKindPasses(ctx, s, o, lightest)
                               ? PdcGrowth{}
                               : PdcGrowthOf(ctx, s, o, omega_lb, q_lb);
  int heavier_idx = kGrid - 1;  // the last piece's raw grid index: the pieces go heaviest first
  std::size_t passed_from = 0;  // pieces 1 to this were passed over together (first.At bounds them)
  for (std::size_t j = edges.size() < 3 ? 0 : edges.size() - 2; j > 0; --j) {
    const double target = std::min(bound, cutoff);
    if (!f.every_capacity_piece && first.At(edges[j + 1]) >= target) {
      // So are the lighter pieces': a smaller budget scores no better (BudgetScore), and the
      // target only falls.
      loads->pieces_skipped += static_cast<long long>(j);
      passed_from = j;
      break;
    }
    const double mass_kg = PairVehicleKg(ctx, s, pi, o, edges[j], floor_kg);
    loads->Reset(mass_kg);
    double w = 0, q = 0;
    int idx = first_idx;
    HoverGridPointInBracket(f, ctx.grids[pi], loads, &idx, heavier_idx, &w, &q);
    heavier_idx = idx;
    // The piece's bound from the first piece's terms (PdcGrowth); -inf without it.
    auto grown = [&]() {
      return growth.ok ? GrownStretchBound(first, lightest, growth.Factor(s.mp, w, q), e_floor, edges[j + 1]) : -kInf;
    };
    if (!f.every_capacity_piece && (piece_lb[j] = grown()) >= target) {
      ++loads->pieces_skipped;
      continue;
    }
    if (!f.every_capacity_piece && !e_floor.loads) {
      // The first piece was passed over below the cutoff: its other segments are assembled now
      // (once; the tests of this piece and the lighter ones then take them, SegmentEnergyFloor).
      loads->Reset(mass_lb);
      first = TermsOfPowers(ctx, f, lightest, pi, o, loads, false, true);
      e_floor.loads = loads;
      loads->Reset(mass_kg);
      if ((piece_lb[j] = std::max(first.At(edges[j + 1]), grown())) >= target) {
        ++loads->pieces_skipped;
        continue;
      }
    }
    const ClassPowers p = HoverPowersOfClasses(ctx, s, o, w, q);
    piece_lb[j] = kInf;
    if (!p.Any()) continue;  // no feasible point here (nor in a heavier piece, M1-M3)
    // (Its own stretch power, momentum theory's included, would cost an assembly of the
    // stretch per piece: the keys' measure, docs/search.md#r13, found it not worth it.)
    if (!f.every_capacity_piece && (piece_lb[j] = OwnPdcBound(first, p, e_floor, edges[j + 1])) >= target) {
      ++loads->pieces_skipped;
      continue;
    }
    piece_lb[j] = TermsOfPowers(ctx, f, p, pi, o, loads).At(edges[j + 1]);
    bound = std::min(bound, piece_lb[j]);
  }
  if (f.refine_capacity_pieces && !f.every_capacity_piece && !edges.empty() && std::isfinite(cutoff) &&
      bound < cutoff) {
    for (std::size_t k = 1; k <= passed_from; ++k) piece_lb[k] = first.At(edges[k + 1]);
    bound = RefineLeastPiece(ctx, f, s, pi, o, floor_kg, first_idx, edges, piece_lb, cutoff, loads);
  }
  double irms_lb = lightest.irms_lb;
  if (edges.empty()) {
    const char* why = nullptr;
    bound = CapacityCoupledBound(ctx, f, s, pi, o, floor_kg, first_idx, bound, cutoff, loads, &irms_lb, &why);
    if (why) {
      pruned->Add(why, per_pair);
      return false;
    }
  }
  if (std::isnan(bound)) bound = -kInf;  // no bound (the order needs a number)
  *c = Candidate{bound, s.motor, static_cast<int>(pi), static_cast<int>(o), irms_lb};
  return true;
}

// Rule R11 (docs/search.md#r11): a lossy motor's power is at least its loss floor at R2's
// speed and torque, so a class's key bounds every pair of its motors.
// R11's key of (pi, o) for lossy motors of at least motor_kg whose loss floors are at least
// `loss`'s.
double PropOnlyBound(const SearchContext& ctx, const MissionFacts& f, std::size_t pi, std::size_t o, double motor_kg,
                     const MotorLossFloor& loss, PairLoads* loads) {
  const BatteryOption& bo = ctx.options[o];
  const PropGrid& g = ctx.grids[pi];
  // The floor of the hover's per-rotor power at the vehicle with a pack of pack_kg (loads set
  // to that mass), and R4's terms with it. The raw grid indices (HoverGridPointInBracket) of the first piece and of the last piece
  // (the pieces go heaviest first), which bracket every later piece's.
  int first_idx = -1, heavier_idx = kGrid - 1;
  bool first_call = true;  // the first piece's
  // The floor with the point's raw grid index known to lie in [*lo, hi] (HoverGridPointInBracket).
  auto floor_in = [&](double pack_kg, int* lo, int hi) {
    loads->Reset(VehicleMassKg(ctx, pack_kg, motor_kg, g.mass_kg, ctx.escs.min_mass_kg[o]));
    double omega_lb = 0, q_lb = 0;
    HoverGridPointInBracket(f, g, loads, lo, hi, &omega_lb, &q_lb);
    const double pac_floor_w =
        omega_lb * q_lb + loss.copper_w_per_nm2 * q_lb * q_lb + loss.no_load_torque_nm * omega_lb;  // physics.h
    return kKeyRoundingAllowance * pac_floor_w;
  };
  auto floor_at = [&](double pack_kg) {
    int idx = first_idx;
    const double w = floor_in(pack_kg, &idx, heavier_idx);
    (first_call ? first_idx : heavier_idx) = idx;
    first_call = false;
    return w;
  };
  auto terms_with = [&](double pdc_lb_w, bool stretch_only, std::vector<SegmentEnergyFloor>* floors = nullptr) {
    return ScoreLowerBoundTerms(ctx, f, true, ctx.catalog->props()[pi], *ctx.models[pi], o, loads, pdc_lb_w,
                                stretch_only, floors);
  };
  auto key_of = [](const ScoreBoundTerms& t, double budget_ah) {
    const double b = t.At(budget_ah);
    return std::isnan(b) ? -kInf : b;
  };
  // R13 (docs/search.md#r13): over a capacity range the same key piece by piece, the other
  // pieces assembled only while they can be the least (as PairCandidate).
  std::vector<double> scratch;
  const std::vector<double>& edges = PieceEdges(ctx, f, o, &scratch, true);  // R11's finer pieces
  if (edges.empty()) {
    // R15 (docs/search.md#r15): min_energy over a capacity range, the key raised by the pack its
    // energy needs (a key above the range's largest pack is left: the pairs' R15 refuses them).
    const double key = key_of(terms_with(floor_at(bo.mass_lo_kg), false), bo.capacity_hi_ah);
    bool over_range = false;
    return RaisedByNeededCapacity(*ctx.mission, bo, key, kInf, &over_range, [&](double capacity_ah) {
      return key_of(terms_with(floor_in(PackMassLowerBoundKg(bo, capacity_ah), &first_idx, kGrid - 1), false),
                    bo.capacity_hi_ah);
    });
  }
  const ScoreBoundTerms first = terms_with(floor_at(bo.mass_lo_kg), false, &loads->floors[1]);
  double least = key_of(first, edges[1]);
  for (std::size_t j = edges.size() - 2; j > 0; --j) {
    if (!f.every_capacity_piece && key_of(first, edges[j + 1]) >= least) {
      loads->pieces_skipped += static_cast<long long>(j);  // and the lighter pieces (as PairCandidate)
      break;
    }
    const double pdc_lb_w = floor_at(PackMassLowerBoundKg(bo, edges[j]));
    if (!f.every_capacity_piece) {
      // The first piece's terms with the stretch's drive term at this piece's floor (its own
      // stretch power is at least that and the first's, M1-M3) and its other segments' terms
      // at that floor (OtherEnergyAtLeastJ).
      // (Its own stretch power with these other segments, the pairs' next test, passed over
      // 1 k more of the capacity-sized quadcopter's 181 k pieces: not taken.)
      const double avionics_w = ctx.mission->vehicle.avionics_power_w;
      ScoreBoundTerms grown = first;
      grown.p_stretch_w = first.StretchPowerAtLeastW(pdc_lb_w, avionics_w);
      grown.e_other_j = OtherEnergyAtLeastJ(loads->floors[1], pdc_lb_w, avionics_w);  // a lighter vehicle's terms
      if (key_of(grown, edges[j + 1]) >= least) {
        ++loads->pieces_skipped;
        continue;
      }
    }
    least = std::min(least, key_of(terms_with(pdc_lb_w, false), edges[j + 1]));
  }
  return least;
}

// Every (propeller R0 lets through, option) with R11's key for the motors of class c, sorted
// by (key, option, propeller); with lossy false (motors R11 does not apply to) every key is
// -inf, in option then propeller order.
std::vector<PropKey> ClassKeys(const SearchContext& ctx, const MissionFacts& f, const MotorClass& c, bool lossy) {
  PairLoads loads(*ctx.mission);
  std::vector<PropKey> keys;
  keys.reserve(f.frame_ok_props.size() * ctx.options.size());
  for (std::size_t o = 0; o < ctx.options.size(); ++o) {
    for (const int pi : f.frame_ok_props) {
      const double b = lossy ? PropOnlyBound(ctx, f, static_cast<std::size_t>(pi), o, c.mass_kg, c.loss, &loads) : -kInf;
      keys.push_back(PropKey{b, pi, static_cast<int>(o)});
    }
  }
  if (lossy) {
    std::sort(keys.begin(), keys.end(), [](const PropKey& a, const PropKey& b) {
      if (a.bound != b.bound) return a.bound < b.bound;
      return a.option != b.option ? a.option < b.option : a.prop < b.prop;
    });
  }
  return keys;
}

// R11's classes of the set-up motors (null: skipped or refused): per motor its class, the last
// class (lightest mass 0, no loss floor) for the motors R11 does not apply to (a drive that
// may create energy); and the classes.
std::vector<int> MotorClasses(const std::vector<const MotorSetup*>& setups, std::vector<MotorClass>* classes) {
  std::vector<std::size_t> lossy;
  for (std::size_t i = 0; i < setups.size(); ++i) {
    if (setups[i] && setups[i]->lossy) lossy.push_back(i);
  }
  std::stable_sort(lossy.begin(), lossy.end(),
                   [&](std::size_t a, std::size_t b) { return setups[a]->mass_kg < setups[b]->mass_kg; });
  std::vector<int> cls(setups.size(), -1);
  classes->clear();
  for (const std::size_t i : lossy) {
    const MotorSetup& s = *setups[i];
    if (classes->empty() || s.mass_kg >= kMotorClassMassRatio * classes->back().mass_kg) {
      classes->push_back(MotorClass{s.mass_kg, s.loss});
    }
    MotorLossFloor& floor = classes->back().loss;
    floor.copper_w_per_nm2 = std::min(floor.copper_w_per_nm2, s.loss.copper_w_per_nm2);
    floor.no_load_torque_nm = std::min(floor.no_load_torque_nm, s.loss.no_load_torque_nm);
    cls[i] = static_cast<int>(classes->size()) - 1;
  }
  classes->push_back(MotorClass{});  // the class without R11
  for (std::size_t i = 0; i < setups.size(); ++i) {
    if (setups[i] && !setups[i]->lossy) cls[i] = static_cast<int>(classes->size()) - 1;
  }
  return cls;
}

// The motors of a search set up on `threads` threads (null where skipped or refused; the
// counts of SkipMotor and MotorSetUp in *pruned, *skipped).
std::vector<std::unique_ptr<MotorSetup>> SetUpMotors(const SearchContext& ctx, const MissionFacts& f, int threads,
                                                     RuleCounts* pruned, long long* skipped) {
  const auto& motors = ctx.catalog->motors();
  const long long per_motor = CombinationsPerMotor(ctx);
  std::vector<std::unique_ptr<MotorSetup>> out(motors.size());
  std::vector<RuleCounts> thread_pruned(static_cast<std::size_t>(std::max(1, threads)));
  std::vector<long long> thread_skipped(thread_pruned.size(), 0);
  ForEachOnThreads(motors.size(), threads, [&](int tid, std::size_t mi) {
    if (SkipMotor(motors[mi], per_motor, &thread_pruned[tid], &thread_skipped[tid])) return;
    auto s = std::make_unique<MotorSetup>();
    if (MotorSetUp(ctx, f, mi, s.get(), &thread_pruned[tid])) out[mi] = std::move(s);
  });
  for (std::size_t t = 0; t < thread_pruned.size(); ++t) {
    thread_pruned[t].MergeInto(pruned);
    *skipped += thread_skipped[t];
  }
  return out;
}

std::vector<const MotorSetup*> Pointers(const std::vector<std::unique_ptr<MotorSetup>>& setups) {
  std::vector<const MotorSetup*> p;
  for (const auto& s : setups) p.push_back(s.get());
  return p;
}

CandidateList BuildCandidates(const SearchContext& ctx, int threads) {
  const MissionFacts f = StageFourFacts(ctx);
  RuleCounts pruned;
  CandidateList out;
  const std::vector<std::unique_ptr<MotorSetup>> setups = SetUpMotors(ctx, f, threads, &pruned, &out.skipped_without_mass);
  std::vector<MotorClass> classes;
  const std::vector<int> cls = MotorClasses(Pointers(setups), &classes);
  std::vector<std::vector<Candidate>> thread_cands(static_cast<std::size_t>(std::max(1, threads)));
  std::vector<RuleCounts> thread_pruned(thread_cands.size());
  ForEachOnThreads(setups.size(), threads, [&](int tid, std::size_t mi) {
    if (!setups[mi]) return;
    const MotorSetup& s = *setups[mi];
    PairLoads loads(*ctx.mission), key_loads(*ctx.mission);
    for (std::size_t o = 0; o < ctx.options.size(); ++o) {
      if (std::isnan(s.w_nl[o])) continue;  // R1 (MotorSetUp)
      for (const int pi : f.frame_ok_props) {
        Candidate c;
        if (!PairCandidate(ctx, f, s, static_cast<std::size_t>(pi), o, &loads, &c, &thread_pruned[tid])) continue;
        if (s.lossy) {  // R11
          const MotorClass& k = classes[static_cast<std::size_t>(cls[mi])];
          c.bound = std::max(c.bound, PropOnlyBound(ctx, f, static_cast<std::size_t>(pi), o, k.mass_kg, k.loss, &key_loads));
        }
        thread_cands[tid].push_back(c);
      }
    }
  });
  for (std::size_t t = 0; t < thread_cands.size(); ++t) {
    out.candidates.insert(out.candidates.end(), thread_cands[t].begin(), thread_cands[t].end());
    thread_pruned[t].MergeInto(&pruned);
  }
  pruned.MergeInto(&out.pruned_by);
  return out;
}

double PropellerKeyBound(const SearchContext& ctx, int prop, int option, int motor) {
  const MotorEntry& mo = ctx.catalog->motors()[static_cast<std::size_t>(motor)];
  PairLoads loads(*ctx.mission);
  return PropOnlyBound(ctx, StageFourFacts(ctx), static_cast<std::size_t>(prop), static_cast<std::size_t>(option),
                       *mo.mass_kg, LossFloorOf(ScenarioMotorParams(mo, *ctx.mission, nullptr, nullptr)), &loads);
}

bool CandidateBefore(const Candidate& a, const Candidate& b) {
  if (a.bound != b.bound) return a.bound < b.bound;
  if (a.option != b.option) return a.option < b.option;
  if (a.motor != b.motor) return a.motor < b.motor;
  return a.prop < b.prop;
}

}  // namespace dynosize::search_internal
