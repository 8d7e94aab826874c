// KDE Direct's stand sheets end to end (issue 51): every sheet row predicted FORWARD from its
// command and supply voltage through the catalog's motor entry, KDE propeller entry and KDE ESC
// entry, and compared with the measured thrust, DC current and speed.
//
// The operating point is where the drive's torque equals the propeller's at the same speed:
//     K*VDC*TR_eff = R*Irms + KE*omega,  Q = KT*(Irms - Io)        (eqs 42, 48, 49)
//     Q = Q_prop(omega) = CP*rho*n^2*D^5/(2*pi),  T = CT*rho*n^2*D^4   (prop/prop_model.h)
//     IDC = (C1*TR_eff + C0)*Irms                                   (eq 57)
// solved by SolveDriveWithProp (prop/prop_drive.h), TR_eff the command through the ESC's dead
// band and knee (docs/model.md sections 7 and 9), at the site's air density of the sheets.
// Three predictions side by side, each with the same propeller entry:
//   dynosize   the motor entry's datasheet values through the KDE in-system law (IS1, IS2 of
//              catalog/in_system.h) fitted WITHOUT this motor (stand/in_system_fit.h,
//              LeaveOneMotorOut), and the KDE ESC entry with the throttle-offset prior of the
//              other motors (the median of their fitted dead bands) as its dead band;
//   plain DC   the hobby calculators' DC model with the datasheet values (stand/dc_baseline.h,
//              model/dc_motor.h): TR*VDC = R*I + n/Kv, I = Io + Q/KT_dc, IDC = TR*I, Io
//              constant, the command as the duty (no offset, no knee);
//   rms, datasheet  dynosize's rms model (eqs 42-59) with the datasheet values (no law) and the
//              same ESC as the dynosize column: what the law alone adds.
// Errors: per sweep (one motor, propeller and supply voltage) the median over its rows of
// |pred/meas - 1|; per motor and overall the median over the sweeps.
//
// The propeller entries (catalog/kde_direct_sheets.json) were built from the same sheets'
// thrust and torque at measured speed, so the thrust error mostly tests the speed prediction
// (T ~ omega^2: a 5 % speed error is about a 10 % thrust error) and the current tests the
// motor + ESC at the propeller's measured torque law.
//
// No I/O: the caller reads the sheets (importers/kde_sheets.h) and loads the catalog.
#pragma once

#include <string>
#include <vector>

#include "catalog/catalog.h"
#include "importers/kde_sheets.h"
#include "stand/in_system_fit.h"

namespace dynosize::stand {

// The site's air density of KDE's sheets, kg/m^3: 1.225 over the median ratio of KDE's
// sea-level thrust estimate to the measured thrust (importers/kde_catalog.cc; the propeller
// entries' CT, CP are at this density). KdeSiteDensityKgM3 recomputes it from the sheets.
inline constexpr double kKdeSiteRhoKgM3 = 1.117;

// 1.225 kg/m^3 / median(thrust_sealevel_est_n / thrust_n) over the rows with both (thrust > 2 N);
// DataError when no row has a sea-level estimate.
double KdeSiteDensityKgM3(const std::vector<KdeSheetMotor>& sheets);

// The catalog id of a sheet's propeller label: "30.5x9.7 DUAL" -> "kde_p_30.5x9.7x2" (TRIPLE: x3);
// "" when the label is not "<D>x<P> DUAL|TRIPLE".
std::string KdePropId(const std::string& label);

struct KdeEndToEndOptions {
  double rho_kg_m3 = kKdeSiteRhoKgM3;
  std::string esc_id = "kde_e_uas125uvc";
  // The in-system law's form (the catalog's KDE law: R and Io scaled, no r_add, no io_speed).
  LawForm form{false, false};
};

// Median over sweeps of the per-sweep median |pred/meas - 1|, and (bias) the same signed.
struct ThrustCurrentSpeedErrors {
  double thrust = 0.0, idc = 0.0, rpm = 0.0;
  double thrust_bias = 0.0, idc_bias = 0.0, rpm_bias = 0.0;
};

struct KdeEndToEndMotor {
  std::string name;      // the sheet's ("KDE5215XF-330")
  std::string motor_id;  // the catalog's ("hl_m_kde5215xf_330")
  bool law_left_out = true;  // false: the sheet has no torque, so the law (fitted on the motors
                             // with torque) never saw it anyway
  double deadband_prior = 0.0;  // the dead band of the dynosize column
  int sweeps = 0, points = 0;
  int sweeps_without_prop = 0;  // skipped: no catalog entry for the sweep's propeller
  int unconverged = 0;          // rows of any column whose solve did not converge (skipped)
  ThrustCurrentSpeedErrors dynosize, plain_dc, rms_datasheet;
};

struct KdeEndToEndReport {
  std::vector<KdeEndToEndMotor> motors;
  ThrustCurrentSpeedErrors dynosize, plain_dc, rms_datasheet;  // over every sweep of every motor
  int sweeps = 0, points = 0, sweeps_without_prop = 0, unconverged = 0;
  std::vector<std::string> skipped;  // one line per skipped sweep or motor, with the reason
  double rho_kg_m3 = 0.0;
  // Markdown: one row per motor and "all", the three columns of thrust / IDC / rpm errors.
  std::string Table() const;
  // One line per column: the overall signed biases (thrust / IDC / rpm).
  std::string Biases() const;
};

// Sheet motors without a catalog entry of the same name are skipped (named in `skipped`).
// `raw` is the catalog loaded WITHOUT the in-system law (Catalog::Load(dir, false)): the
// law is applied here, fitted without each motor. Throws UsageError when the ESC is absent,
// DataError when fewer than 3 sheet motors have torque (LeaveOneMotorOut).
KdeEndToEndReport KdeSheetsEndToEnd(const std::vector<KdeSheetMotor>& sheets, const Catalog& raw,
                                    const KdeEndToEndOptions& options = {});

}  // namespace dynosize::stand
