// Calibrate's starting and held values: KE and R from U = R*I + KE*omega (eq 48, or eq 42 with
// the AC columns) and KT and Io from Q = KT*Irms - KT*Io by linear least squares; held values
// from the priors; and Io where the log cannot identify it (label, motor prior or the no-load
// prior of catalog/noload_prior.h). Internal to src/calibration.
#pragma once

#include "calibration/prepared_fit.h"

namespace dynosize::calibration::internal {

// Prepare, stage 4: starting values (linear sub-problems) and held values (priors), returned in
// the internal form (KT as the ratio f, C1 as the excess s) inside the box.
void StartingValues(const logs::SteadyTable& t, const CalibrationOptions& o, const LogColumns& c, Prepared* pr);
// Io where the log cannot identify it (no torque, no no-load rows): the label (--io-label), else
// the motor prior, else the no-load prior - never 0. Sets motor.io_a, params[kIo] and io_source.
void HeldIo(const Prepared& pr, const logs::SteadyTable& t, const CalibrationOptions& o, CalibrationResult* res);

}  // namespace dynosize::calibration::internal
