#include "rotor/per3.h"

#include <cmath>

namespace dynosize {
namespace {

// Within the block of rows [begin, end) (one rpm): linear in airspeed.
bool InBlock(const std::vector<Per3Row>& rows, std::size_t begin, std::size_t end, double v, double* t, double* q) {
  for (std::size_t i = begin; i + 1 < end; ++i) {
    const Per3Row& a = rows[i];
    const Per3Row& b = rows[i + 1];
    if (v >= a.airspeed_m_s && v <= b.airspeed_m_s && b.airspeed_m_s > a.airspeed_m_s) {
      const double s = (v - a.airspeed_m_s) / (b.airspeed_m_s - a.airspeed_m_s);
      *t = a.thrust_n + s * (b.thrust_n - a.thrust_n);
      *q = a.torque_nm + s * (b.torque_nm - a.torque_nm);
      return true;
    }
  }
  if (begin < end && v == rows[begin].airspeed_m_s) {
    *t = rows[begin].thrust_n;
    *q = rows[begin].torque_nm;
    return true;
  }
  return false;
}

}  // namespace

bool Per3At(const Per3Table& table, double rpm, double v, double* thrust_n, double* torque_nm) {
  const std::vector<Per3Row>& r = table.rows;
  // Block boundaries: a new block starts where the rpm changes.
  std::size_t lo_begin = 0, lo_end = 0;
  bool have_lo = false;
  for (std::size_t begin = 0; begin < r.size();) {
    std::size_t end = begin;
    while (end < r.size() && r[end].rpm == r[begin].rpm) ++end;
    const double block_rpm = r[begin].rpm;
    if (block_rpm <= rpm) {
      lo_begin = begin;
      lo_end = end;
      have_lo = true;
    } else {
      if (!have_lo) return false;
      double t0, q0, t1, q1;
      if (!InBlock(r, lo_begin, lo_end, v, &t0, &q0) || !InBlock(r, begin, end, v, &t1, &q1)) return false;
      const double s = (rpm - r[lo_begin].rpm) / (block_rpm - r[lo_begin].rpm);
      *thrust_n = t0 + s * (t1 - t0);
      *torque_nm = q0 + s * (q1 - q0);
      return true;
    }
    begin = end;
  }
  // rpm at or above the last block: only an exact match is inside.
  if (have_lo && r[lo_begin].rpm == rpm) return InBlock(r, lo_begin, lo_end, v, thrust_n, torque_nm);
  return false;
}

}  // namespace dynosize
