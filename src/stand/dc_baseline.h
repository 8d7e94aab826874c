// The plain first-order DC motor model that hobby calculators use (DriveCalc, eCalc), kept as
// the baseline that dynosize's rms model (model/drive.h, eqs 42-59) must beat on stand tables.
//
// A DC motor of label Kv (rpm per volt), resistance R and no-load current Io:
//     KT_dc = 60/(2*pi*Kv)            [N*m/A]  (= 1/Kv in V*s/rad, so KE_dc = KT_dc)
//     I     = Io + Q/KT_dc            (motor current; Q the shaft torque)
//     U     = n/Kv + R*I              (motor voltage; n in rpm)
// (model.md section 10 last paragraph: DriveCalc's 8,214 measured points reproduce the label Kv
// under U = n/Kv + R*I.) The ESC is a lossless chopper of duty d = throttle:
//     U = d*VDC,   IDC = d*I          (VDC*IDC = U*I)
// For the comparison to be about the model and not the numbers, the baseline gets the numbers a
// DC calculator would get for the same parts (DcBaselineNumbers::kDatasheet): label Kv, the
// datasheet resistance R_dc of motor + ESC and the datasheet (DC) no-load current. The catalog
// stores the rms circuit's numbers (catalog/conventions.h: rm_ohm = 0.7492*R_dc, io_a =
// Io_dc/1.1095), so the baseline converts them back. At full throttle, no load, it reaches
// n = Kv*(VDC - R*Io) as the label says.
//
// No I/O, no allocation.
#pragma once

#include <functional>

#include "catalog/catalog.h"

namespace dynosize {

struct DcMotor {
  double kv_rpm_per_v = 0.0;
  double r_ohm = 0.0;
  double io_a = 0.0;
  // KT_dc = 60/(2*pi*Kv), N*m/A.
  double kt_nm_per_a() const;
};

// Which numbers the baseline gets.
enum class DcBaselineNumbers {
  // What a DC calculator is given (the default): R = R_dc + RESC_dc, Io = Io_dc, with
  //   R_dc    the entry's rm_dc_ohm (the source's own DC-circuit number) when it has one, else
  //           rm_ohm/0.7492 (the DC equivalent of the rms circuit's Rm);
  //   RESC_dc resc_ohm/0.7492 (RESC sits in series with Rm in eq 48, so it converts alike);
  //   Io_dc   1.1095*io_a (eq 56 at full throttle).
  // The factors are catalog/conventions.h's (kRmsPerDcResistance, kIdealIdcPerIrmsPerThrottle).
  // Under an ideal, unsaturated ESC the rms model then gives the same DC current at any
  // (speed, torque) as this baseline, up to the rounding of rm_ohm against rm_dc_ohm: the
  // comparison isolates the ESC model (C1, C0, the saturation knee). Brushed motors need no
  // conversion (K = kp = 1).
  kDatasheet,
  // The catalog's rms numbers fed unchanged to the DC model: R = rm_ohm + resc_ohm, Io = io_a.
  // Not a DC calculator's view of the parts: R is 0.7492 x and Io 0.90 x what the datasheet
  // says. Kept to show what mixing the conventions does.
  kAsStored,
};

// The baseline for a catalog motor + ESC: label Kv (the catalog's kv_rpm_per_v, else derived
// from KE by model.md section 8) and R, Io as chosen above.
DcMotor DcMotorFromCatalog(const MotorEntry& motor, const EscEntry& esc,
                           DcBaselineNumbers numbers = DcBaselineNumbers::kDatasheet);

// "datasheet" | "as-stored" (the CLI's --baseline names).
const char* DcBaselineName(DcBaselineNumbers numbers);

struct DcPoint {
  double omega_rad_s = 0.0;
  double torque_nm = 0.0;
  double current_a = 0.0;  // motor current I
  double voltage_v = 0.0;  // motor voltage U
  double duty = 0.0;       // U/VDC: the throttle the plain model needs (> 1: not reachable)
  double idc_a = 0.0;      // d*I
  double pdc_w = 0.0;      // VDC*IDC
};

// Speed and torque given (a stand row at its measured rpm): I, U, duty and IDC.
DcPoint DcAtSpeedTorque(const DcMotor& m, double vdc_v, double omega_rad_s, double torque_nm);

// Throttle and a constant torque given: n = Kv*(d*VDC - R*I), floored at 0 (stalled).
DcPoint DcAtThrottleTorque(const DcMotor& m, double vdc_v, double throttle, double torque_nm);

// Throttle and a load torque Q(omega) (non-decreasing, Q(0) >= 0, e.g. a propeller) given: the
// speed where d*VDC = KT_dc*omega + R*(Io + Q(omega)/KT_dc), by bisection on [0, d*VDC/KT_dc]
// (the residual falls monotonically in omega), to 1e-10 relative.
DcPoint DcAtThrottleLoad(const DcMotor& m, double vdc_v, double throttle,
                         const std::function<double(double)>& torque_of_omega_nm);

}  // namespace dynosize
