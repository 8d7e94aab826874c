// The plain first-order DC model (model/dc_motor.h) fitted to a log: the baseline calibrate's
// held-out errors are reported beside (the project's rule: the model to beat on real data is the
// plain DC model; report it side by side, and find out why where the rms model loses).
//
// On the fit rows with a speed, the lossless chopper of the DC model gives the motor's voltage
// and current from the log, U = d*VDC and I = IDC/d (d the throttle, or the assumed throttle of
// a log without one, through the throttle offset (dead band) dynosize's fit found on the same
// rows, as a careful user would correct the command: without it a Tyto log of a KDE 4014XF-300
// with a -0.078 offset fits Kv 1,100-1,300 rpm/V and R 0.74 ohm, and the held-out speed
// collapses to 0, issue 55), and
//     U = n/Kv + R*I                 Kv and R by linear least squares (LinearCircuitStart), or
//                                    with the label's Kv held (the numbers a DC calculator has:
//                                    label Kv, R and Io) and R alone (ResistanceWithKeHeld)
//     Io = mean(I - Q/KT_dc)         over rows with torque, KT_dc = 60/(2*pi*Kv)
// (no torque: Io does not enter the speed predicted from the current, and is 0). Nothing is
// bounded: this is what a DC calculator fed the log's own least-squares numbers would predict.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "logs/steady_table.h"
#include "model/dc_motor.h"

namespace dynosize::identification {

struct DcFit {
  DcMotor motor;
  double deadband = 0.0;  // the throttle offset the duty was corrected by
  // At least 2 rows with speed, current and a positive duty, Kv > 0 and R >= 0 (a careful user
  // keeps no negative resistance): else `why` says which, and no error is reported for it.
  bool ok = false;
  std::string why;
};

// kv_label_rpm_per_v <= 0: Kv fitted too. deadband: the command's offset (0: none).
DcFit FitDcMotor(const logs::SteadyTable& t, const std::vector<std::size_t>& rows, double assumed_throttle,
                 double kv_label_rpm_per_v = 0.0, double deadband = 0.0);

// Predictions of the DC model for log row i (NaN where it cannot predict): with torque, the
// speed and DC current at the row's throttle and torque (DcAtThrottleTorque); the speed from the
// row's measured DC current (I = IDC/d, the torque that current gives).
struct DcRowPrediction {
  double omega_at_torque_rad_s;
  double idc_at_torque_a;
  double omega_from_idc_rad_s;
};
DcRowPrediction PredictDcRow(const DcMotor& m, const logs::SteadyTable& t, std::size_t i, double assumed_throttle,
                             double deadband = 0.0);

}  // namespace dynosize::identification
