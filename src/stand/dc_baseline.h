// The plain first-order DC motor model that hobby calculators use (DriveCalc, eCalc), kept as
// the baseline that dynosize's rms model (model/drive.h, eqs 42-59) must beat on stand tables.
//
// A DC motor of label Kv (rpm per volt), resistance R and no-load current Io:
//     KT_dc = 60/(2*pi*Kv)            [N*m/A]  (= 1/Kv in V*s/rad, so KE_dc = KT_dc)
//     I     = Io + Q/KT_dc            (motor current; Q the shaft torque)
//     U     = n/Kv + R*I              (motor voltage; n in rpm)
// (docs/model.md section 10 last paragraph: DriveCalc's 8,214 measured points reproduce the label Kv
// under U = n/Kv + R*I.) The ESC is a lossless chopper of duty d = throttle:
//     U = d*VDC,   IDC = d*I          (VDC*IDC = U*I)
// For the comparison to be about the model and not the numbers, the baseline gets the numbers a
// DC calculator would get for the same parts (DcBaselineNumbers::kDatasheet): label Kv, the
// datasheet resistance R_dc of motor + ESC and the datasheet (DC) no-load current. The catalog
// stores the rms circuit's numbers (catalog/conventions.h: rm_ohm = 0.7492*R_dc, io_a =
// Io_dc/1.1095), so the baseline converts them back. At full throttle, no load, it reaches
// n = Kv*(VDC - R*Io) as the label says.
//
// The model itself is model/dc_motor.h; this file gives it a catalog motor's numbers.
#pragma once

#include "catalog/catalog.h"
#include "model/dc_motor.h"

namespace dynosize {

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
// from KE by docs/model.md section 8) and R, Io as chosen above.
DcMotor DcMotorFromCatalog(const MotorEntry& motor, const EscEntry& esc,
                           DcBaselineNumbers numbers = DcBaselineNumbers::kDatasheet);

// "datasheet" | "as-stored" (the CLI's --baseline names).
const char* DcBaselineName(DcBaselineNumbers numbers);

}  // namespace dynosize
