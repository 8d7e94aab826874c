// The plain first-order DC motor model that hobby calculators use (DriveCalc, eCalc), kept as
// the baseline that dynosize's rms model (model/drive.h, eqs 42-59) must beat on stand tables
// (stand/dc_baseline.h gives it a catalog motor's numbers) and on fitted logs (calibrate's
// held-out comparison, identification/dc_fit.h).
//
// A DC motor of label Kv (rpm per volt), resistance R and no-load current Io:
//     KT_dc = 60/(2*pi*Kv)            [N*m/A]  (= 1/Kv in V*s/rad, so KE_dc = KT_dc)
//     I     = Io + Q/KT_dc            (motor current; Q the shaft torque)
//     U     = n/Kv + R*I              (motor voltage; n in rpm)
// (docs/model.md section 10 last paragraph: DriveCalc's 8,214 measured points reproduce the label Kv
// under U = n/Kv + R*I.) The ESC is a lossless chopper of duty d = throttle:
//     U = d*VDC,   IDC = d*I          (VDC*IDC = U*I)
//
// No I/O, no allocation.
#pragma once

#include <functional>

namespace dynosize {

struct DcMotor {
  double kv_rpm_per_v = 0.0;
  double r_ohm = 0.0;
  double io_a = 0.0;
  // KT_dc = 60/(2*pi*Kv), N*m/A.
  double kt_nm_per_a() const;
};

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
