// Synthetic steady logs made by the model itself (src/model/drive.h), with seeded noise, for the
// calibration tests: the true parameters are known, so a fit can be checked against them.
#pragma once

#include <cmath>
#include <random>
#include <vector>

#include "logs/steady_table.h"
#include "model/drive.h"

namespace dynosize::calibration::testing_util {

struct SyntheticSpec {
  MotorParams motor;
  EscParams esc;
  std::vector<double> vdc_v = {11.1, 14.8};
  std::vector<double> throttles;             // default: 0.3, 0.35, ..., 1.0
  std::vector<double> prop_c = {2.0e-7, 3.2e-7};  // Q = c*omega^2, two propellers
  double noise_rel = 0.005;  // Gaussian, relative, on every measured column (seeded)
  unsigned seed = 12345;
  int outliers = 0;          // rows whose idc_a is multiplied by 1.25
  bool ac = true;            // vll_rms_v, irms_a, pac_w present
  bool torque = true;
  bool throttle_column = true;
};

// A BLDC of about 900 rpm/V with a 30 A ESC that saturates at 90 % throttle (docs/model.md section 7).
inline SyntheticSpec DefaultSpec() {
  SyntheticSpec s;
  s.motor.ke_v_s_per_rad = kVllRmsPerVdc / (900.0 * kRadPerSecPerRpm);
  s.motor.kt_nm_per_a = kPacPerVllIrms * s.motor.ke_v_s_per_rad * 0.97;  // KT/KE a little off ideal
  s.motor.rm_ohm = 0.12;
  s.motor.io_a = 0.5;
  s.esc.resc_ohm = 0.03;
  // A physical ESC (docs/model.md section 10: c0 >= 0, c1 + c0 = 1.16 >= 1.1095): switching losses
  // of about 4 % of PAC.
  s.esc.c1 = 1.12;
  s.esc.c0 = 0.04;
  s.esc.tr_sat = 0.9;
  s.esc.sat_slope = 0.6;
  for (int k = 0; k <= 14; ++k) s.throttles.push_back(0.3 + 0.05 * k);
  return s;
}

// DefaultSpec's drive with a throttle offset (a negative dead band, docs/model.md section 9) and
// no saturation knee, so that the offset is what the fit must find.
inline SyntheticSpec ThrottleOffsetSpec() {
  SyntheticSpec s = DefaultSpec();
  s.esc.deadband = -0.08;
  s.esc.tr_sat = 1.0;
  s.esc.sat_slope = 1.0;
  return s;
}

inline logs::SteadyTable MakeSyntheticLog(const SyntheticSpec& s) {
  using logs::Column;
  const Drive drive(s.motor, s.esc);
  std::mt19937 rng(s.seed);
  std::normal_distribution<double> noise(0.0, s.noise_rel);
  logs::SteadyTable t;
  t.file = "synthetic.csv";
  t.format = logs::LogFormat::kCanonical;
  std::vector<Column> cols = {Column::kTimeS, Column::kVdcV, Column::kOmegaRadS, Column::kIdcA};
  if (s.throttle_column) cols.push_back(Column::kThrottle);
  if (s.torque) cols.push_back(Column::kTorqueNm);
  if (s.ac) {
    cols.push_back(Column::kVllRmsV);
    cols.push_back(Column::kIrmsA);
    cols.push_back(Column::kPacW);
  }
  for (Column c : cols) t.info[static_cast<int>(c)].present = true;
  std::size_t row = 0;
  for (double v : s.vdc_v) {
    for (double c : s.prop_c) {
      for (double tr : s.throttles) {
        const OperatingPoint p = drive.AtLoad(v, tr, TorqueLaw{0.0, 0.0, c});
        auto noisy = [&](double x) { return x * (1.0 + noise(rng)); };
        t.Mutable(Column::kTimeS).push_back(static_cast<double>(row));
        t.Mutable(Column::kVdcV).push_back(noisy(v));
        t.Mutable(Column::kOmegaRadS).push_back(noisy(p.omega_rad_s));
        double idc = noisy(p.idc_a);
        if (static_cast<int>(row) < s.outliers * 7 && row % 7 == 3) idc *= 1.25;
        t.Mutable(Column::kIdcA).push_back(idc);
        if (s.throttle_column) t.Mutable(Column::kThrottle).push_back(tr);
        if (s.torque) t.Mutable(Column::kTorqueNm).push_back(noisy(p.torque_nm));
        if (s.ac) {
          t.Mutable(Column::kVllRmsV).push_back(noisy(p.vll_rms_v));
          t.Mutable(Column::kIrmsA).push_back(noisy(p.irms_a));
          t.Mutable(Column::kPacW).push_back(noisy(p.pac_w));
        }
        t.source_line.push_back(row + 2);
        t.samples.push_back(1);
        ++row;
      }
    }
  }
  return t;
}

}  // namespace dynosize::calibration::testing_util
