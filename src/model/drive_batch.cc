#include "model/drive_batch.h"

#include <algorithm>
#include <cmath>

#include "common/units.h"
#include "model/physics.h"

// The output arrays never alias the inputs nor each other (PointColumns' contract): tell GCC's
// vectoriser so, instead of letting it version ~20 pointers with run-time overlap checks. Clang
// is left to its own analysis: a forced "loop vectorize(enable)" it cannot honour (as under the
// sanitizers) is a -Wpass-failed warning, an error with DYNOSIZE_WERROR.
#if defined(__GNUC__) && !defined(__clang__)
#define DYNOSIZE_VECTOR_LOOP _Pragma("GCC ivdep")
#else
#define DYNOSIZE_VECTOR_LOOP
#endif

// Each chunk loop is built twice on x86-64 with GCC, for AVX2 and for the baseline (SSE2), and
// the loader picks the one the processor runs: the checks mix 64-bit lanes with bytes, which the
// vectoriser handles with AVX2 only. Both give the same numbers: neither uses fused multiply-add
// (not part of the AVX2 target), so each operation rounds as Drive's scalar code does.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define DYNOSIZE_SIMD_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define DYNOSIZE_SIMD_CLONES
#endif

namespace dynosize {

PointColumns PointColumns::From(std::size_t i) const {
  PointColumns c = *this;
  for (double** p : {&c.vdc_v, &c.throttle, &c.throttle_effective, &c.rpm, &c.omega_rad_s, &c.torque_nm, &c.irms_a,
                     &c.vll_rms_v, &c.pac_w, &c.idc_a, &c.pdc_w, &c.pesc_w, &c.pmech_w, &c.eta_motor, &c.eta_esc,
                     &c.eta_system}) {
    *p += i;
  }
  c.saturated += i;
  c.feasible += i;
  c.limits += i;
  return c;
}

void PointColumns::Set(std::size_t i, const OperatingPoint& p) const {
  vdc_v[i] = p.vdc_v;
  throttle[i] = p.throttle;
  throttle_effective[i] = p.throttle_effective;
  rpm[i] = p.rpm;
  omega_rad_s[i] = p.omega_rad_s;
  torque_nm[i] = p.torque_nm;
  irms_a[i] = p.irms_a;
  vll_rms_v[i] = p.vll_rms_v;
  pac_w[i] = p.pac_w;
  idc_a[i] = p.idc_a;
  pdc_w[i] = p.pdc_w;
  pesc_w[i] = p.pesc_w;
  pmech_w[i] = p.pmech_w;
  eta_motor[i] = p.eta_motor;
  eta_esc[i] = p.eta_esc;
  eta_system[i] = p.eta_system;
  saturated[i] = p.saturated;
  feasible[i] = p.feasible();
  limits[i] = p.limits;
}

PointColumnsStorage::PointColumnsStorage(std::size_t n)
    : n_(n), values_(new double[16 * n]), flags_(new bool[2 * n]), limits_(new std::uint32_t[n]) {
  double* v = values_.get();
  for (double** c : {&columns_.vdc_v, &columns_.throttle, &columns_.throttle_effective, &columns_.rpm,
                     &columns_.omega_rad_s, &columns_.torque_nm, &columns_.irms_a, &columns_.vll_rms_v,
                     &columns_.pac_w, &columns_.idc_a, &columns_.pdc_w, &columns_.pesc_w, &columns_.pmech_w,
                     &columns_.eta_motor, &columns_.eta_esc, &columns_.eta_system}) {
    *c = v;
    v += n;
  }
  columns_.saturated = flags_.get();
  columns_.feasible = flags_.get() + n;
  columns_.limits = limits_.get();
}

OperatingPoint PointColumns::Get(std::size_t i) const {
  OperatingPoint p;
  p.vdc_v = vdc_v[i];
  p.throttle = throttle[i];
  p.throttle_effective = throttle_effective[i];
  p.saturated = saturated[i];
  p.omega_rad_s = omega_rad_s[i];
  p.rpm = rpm[i];
  p.torque_nm = torque_nm[i];
  p.irms_a = irms_a[i];
  p.vll_rms_v = vll_rms_v[i];
  p.pac_w = pac_w[i];
  p.idc_a = idc_a[i];
  p.pdc_w = pdc_w[i];
  p.pesc_w = pesc_w[i];
  p.pmech_w = pmech_w[i];
  p.eta_motor = eta_motor[i];
  p.eta_esc = eta_esc[i];
  p.eta_system = eta_system[i];
  p.limits = limits[i];
  return p;
}

namespace {

// Points per pass: the solve writes a chunk's outputs, the check reads them back while they are
// still in the cache (16 arrays of 512 doubles: 64 KiB, in L2).
constexpr std::size_t kChunk = 512;

// The drive's constants, read once per batch (first-order drives only: no extension is set).
struct Constants {
  double kt, ke, io, r, kv, kp, resc, c1, c0, tr_sat, slope;
  explicit Constants(const Drive& d)
      : kt(d.motor().kt_nm_per_a),
        ke(d.motor().ke_v_s_per_rad),
        io(d.motor().io_a),
        r(d.r_total_ohm()),
        kv(d.volt_factor()),
        kp(d.power_factor()),
        resc(d.esc().resc_ohm),
        c1(d.esc().c1),
        c0(d.esc().c0),
        tr_sat(d.esc().tr_sat),
        slope(d.esc().sat_slope) {}
};

inline double Ratio(double num, double den) {
  const double q = num / den;  // computed for every lane, kept only where both are positive
  return ((den > 0.0) & (num > 0.0)) ? q : 0.0;
}

// Drive's Complete for a first-order drive (model/drive.cc), the same expressions in the same
// order, for point i of a chunk: (VDC, TR, omega, I) given, the rest follows. `stalled` clamps
// the torque at 0 as Complete does for kLimitStalled.
inline void CompleteAt(const Constants& k, const PointColumns& o, std::size_t i, double vdc, double thr, double w,
                       double cur, bool stalled) {
  // Section 7's knee; without a dead band the command is its own duty, d = TR.
  const double tre_above = k.tr_sat + k.slope * (thr - k.tr_sat);
  const double tre = thr <= k.tr_sat ? thr : tre_above;
  const double q_free = k.kt * (cur - k.io);                  // (42)
  const double q = (stalled & (q_free < 0.0)) ? 0.0 : q_free;  // std::max(q, 0) as Complete
  const double vll = k.kv * vdc * tre - k.resc * cur;         // (46), (47)
  const double pac = k.kp * vll * cur;                        // (41), (51)
  const double idc = (k.c1 * tre + k.c0) * cur;               // (57)
  const double pdc = vdc * idc;                               // (59)
  const double pm = q * w;                                    // (50)
  o.vdc_v[i] = vdc;
  o.throttle[i] = thr;
  o.throttle_effective[i] = tre;
  o.rpm[i] = RadPerSecToRpm(w);
  o.omega_rad_s[i] = w;
  o.torque_nm[i] = q;
  o.irms_a[i] = cur;
  o.vll_rms_v[i] = vll;
  o.pac_w[i] = pac;
  o.idc_a[i] = idc;
  o.pdc_w[i] = pdc;
  o.pesc_w[i] = pdc - pac;                                    // (52)
  o.pmech_w[i] = pm;
  o.eta_motor[i] = Ratio(pm, pac);                            // (53), (13)
  o.eta_esc[i] = Ratio(pac, pdc);
  o.eta_system[i] = Ratio(pm, pdc);
}

// Drive::Inverse: I from the torque (42), U from (48), the throttle through the knee inverted.
DYNOSIZE_SIMD_CLONES void InverseChunk(const Constants& k, std::size_t m, const BatchInputs& inputs, const PointColumns& columns,
                  std::uint64_t* bits) {
  const BatchInputs in = inputs;  // local copies: the pointers stay in registers
  const PointColumns o = columns;
  DYNOSIZE_VECTOR_LOOP
  for (std::size_t i = 0; i < m; ++i) {
    const double vdc = in.vdc_v[i], w = in.omega_rad_s[i];
    const double cur = in.torque_nm[i] / k.kt + k.io;          // (42)
    const double u = k.r * cur + k.ke * w;                     // (48)
    const double tre = u / (k.kv * vdc);                       // (46)
    const double thr_above = k.tr_sat + (tre - k.tr_sat) / k.slope;
    CompleteAt(k, o, i, vdc, tre <= k.tr_sat ? tre : thr_above, w, cur, false);
    bits[i] = kLimitNone;
  }
}

// Drive::AtLoad with the law Q = a (AtTorque): the root of (49) with c = 0 as PositiveRoot
// computes it, a stall (no non-negative root) at omega = 0 and I = max(U/R, 0).
DYNOSIZE_SIMD_CLONES void AtTorqueChunk(const Constants& k, std::size_t m, const BatchInputs& inputs, const PointColumns& columns,
                   std::uint64_t* bits) {
  const BatchInputs in = inputs;  // local copies: the pointers stay in registers
  const PointColumns o = columns;
  const double b_total = 0.0 + k.kt * k.ke / k.r;  // the law's b = 0 plus KT*KE/R
  const double c_law = 0.0;
  DYNOSIZE_VECTOR_LOOP
  for (std::size_t i = 0; i < m; ++i) {
    const double vdc = in.vdc_v[i], thr = in.throttle[i];
    const double tre_above = k.tr_sat + k.slope * (thr - k.tr_sat);
    const double u = k.kv * vdc * (thr <= k.tr_sat ? thr : tre_above);  // (48) left side
    const double c_total = in.torque_nm[i] + k.kt * k.io - k.kt * u / k.r;
    const double disc = b_total * b_total - 4.0 * c_law * c_total;
    const double root_den = b_total + std::sqrt(disc < 0.0 ? 0.0 : disc);
    // PositiveRoot's conditions as limit bits in 64-bit lanes, the doubles' width (what the
    // vectoriser accepts): the drive stalls where one fails.
    const std::uint64_t stall = (disc >= 0.0 ? 0u : kLimitStalled) | (root_den > 0.0 ? 0u : kLimitStalled) |
                                (c_total <= 0.0 ? 0u : kLimitStalled);
    const bool runs = stall == 0;
    const double root = -2.0 * c_total / root_den;
    const double w = runs ? root : 0.0;
    const double i_run = (u - k.ke * root) / k.r;              // (48)
    const double i_stall = u / k.r;
    const double cur = runs ? i_run : (i_stall < 0.0 ? 0.0 : i_stall);
    CompleteAt(k, o, i, vdc, thr, w, cur, !runs);
    const std::uint64_t overrun = i_run < k.io - 1e-9 ? kLimitOverrunning : 0u;  // below Io, 1 nA slack
    bits[i] = stall != 0 ? stall : overrun;
  }
}

// Drive::AtSpeed: I from (48) at the given speed.
DYNOSIZE_SIMD_CLONES void AtSpeedChunk(const Constants& k, std::size_t m, const BatchInputs& inputs, const PointColumns& columns,
                  std::uint64_t* bits) {
  const BatchInputs in = inputs;  // local copies: the pointers stay in registers
  const PointColumns o = columns;
  DYNOSIZE_VECTOR_LOOP
  for (std::size_t i = 0; i < m; ++i) {
    const double vdc = in.vdc_v[i], thr = in.throttle[i], w = in.omega_rad_s[i];
    const double tre_above = k.tr_sat + k.slope * (thr - k.tr_sat);
    const double u = k.kv * vdc * (thr <= k.tr_sat ? thr : tre_above);
    const double cur = (u - k.ke * w) / k.r;                   // (48)
    const double io = k.io + 0.0 * w;                          // Io(omega) without io1, as AtSpeed
    CompleteAt(k, o, i, vdc, thr, w, cur, false);
    bits[i] = cur < io ? std::uint64_t{kLimitOverrunning} : std::uint64_t{kLimitNone};
  }
}

// Drive::Flag over a chunk: the solve's bits plus the rating limits, in 64-bit lanes (the
// doubles' width: one vectorised loop), then narrowed to the columns' codes and flags.
DYNOSIZE_SIMD_CLONES void FlagChunk(const MotorParams& mp, const EscParams& ep, std::size_t m, const PointColumns& columns,
               std::uint64_t* bits) {
  const PointColumns o = columns;
  DYNOSIZE_VECTOR_LOOP
  for (std::size_t i = 0; i < m; ++i) {
    bits[i] |= RatingLimits<std::uint64_t>(mp, ep, o.vdc_v[i], o.throttle[i], o.irms_a[i], o.idc_a[i], o.pac_w[i],
                                           o.pdc_w[i], o.pesc_w[i], o.pmech_w[i]);
  }
  DYNOSIZE_VECTOR_LOOP
  for (std::size_t i = 0; i < m; ++i) {
    o.limits[i] = static_cast<std::uint32_t>(bits[i]);
    o.feasible[i] = bits[i] == kLimitNone;
  }
  DYNOSIZE_VECTOR_LOOP
  for (std::size_t i = 0; i < m; ++i) o.saturated[i] = o.throttle[i] > ep.tr_sat;
}

BatchInputs Advance(const BatchInputs& in, std::size_t i) {
  BatchInputs a = in;
  for (const double** p : {&a.vdc_v, &a.throttle, &a.torque_nm, &a.omega_rad_s}) {
    if (*p != nullptr) *p += i;
  }
  return a;
}

OperatingPoint SolveOne(const Drive& d, BatchMode mode, const BatchInputs& in, std::size_t i) {
  switch (mode) {
    case BatchMode::kInverse: return d.Inverse(in.vdc_v[i], in.torque_nm[i], in.omega_rad_s[i]);
    case BatchMode::kAtTorque: return d.AtTorque(in.vdc_v[i], in.throttle[i], in.torque_nm[i]);
    case BatchMode::kAtSpeed: break;
  }
  return d.AtSpeed(in.vdc_v[i], in.throttle[i], in.omega_rad_s[i]);
}

}  // namespace

// The chunks of a first-order drive, each solved and then checked.
static void SolveChunks(const Drive& drive, BatchMode mode, std::size_t n, const BatchInputs& in, const PointColumns& out) {
  const Constants k(drive);
  std::uint64_t bits[kChunk];  // the chunk's limit bits
  for (std::size_t begin = 0; begin < n; begin += kChunk) {
    const std::size_t m = std::min(kChunk, n - begin);
    const BatchInputs ci = Advance(in, begin);
    const PointColumns co = out.From(begin);
    switch (mode) {
      case BatchMode::kInverse: InverseChunk(k, m, ci, co, bits); break;
      case BatchMode::kAtTorque: AtTorqueChunk(k, m, ci, co, bits); break;
      case BatchMode::kAtSpeed: AtSpeedChunk(k, m, ci, co, bits); break;
    }
    FlagChunk(drive.motor(), drive.esc(), m, co, bits);
  }
}

void SolveBatch(const Drive& drive, BatchMode mode, std::size_t n, const BatchInputs& in, const PointColumns& out) {
  if (drive.extended()) {
    // Section 9's extensions have no common closed form per point: Drive's scalar path.
    for (std::size_t i = 0; i < n; ++i) out.Set(i, SolveOne(drive, mode, in, i));
    return;
  }
  SolveChunks(drive, mode, n, in, out);
}

}  // namespace dynosize
