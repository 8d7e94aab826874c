// The drive the model's tests share (the paper's pair): a BLDC motor with KE = 3.7745 mV*s/rad
// (about 1,700 rpm/V), Rm 0.12 ohm, Io 0.5 A and KT at its energy bound sqrt(27/10)*KE
// (docs/model.md section 10), and an ESC above the ideal one (C1 + C0 = 1.23 >= 1.1095, eq 56)
// with a saturation knee at 90 % throttle (section 7).
#pragma once

#include "common/units.h"
#include "model/params.h"

namespace dynosize {
namespace paper_drive {

// Without ratings (+inf): every point is feasible unless the throttle or the load says otherwise.
inline MotorParams Motor() {
  MotorParams m;
  m.ke_v_s_per_rad = 0.0037745;
  m.kt_nm_per_a = kPacPerVllIrms * m.ke_v_s_per_rad;
  m.rm_ohm = 0.12;
  m.io_a = 0.5;
  return m;
}

inline EscParams Esc() {
  EscParams e;
  e.resc_ohm = 0.02;
  e.c1 = 1.2;
  e.c0 = 0.03;
  e.tr_sat = 0.9;
  e.sat_slope = 0.61;
  return e;
}

}  // namespace paper_drive
}  // namespace dynosize
