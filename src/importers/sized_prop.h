// A propeller from its size alone (issue 52): "DxP[xB]" in inches and a family (rotor/family.h),
// its blade built by eq B12 and run through the blade-element model with the polar fitted on UIUC's
// propellers (rotor/uiuc_polar.h), written as a catalog propeller entry whose static table and J
// sweeps are the model's, so that every command that takes a catalog propeller takes it
// (prop/prop_model.h reads it like any computed table). Tier "estimated"; its error, measured by
// leaving each measured propeller out of its family (docs/validation.md), is the entry's range.
#pragma once

#include <string>
#include <vector>

#include "catalog/entries.h"
#include "common/json_file.h"
#include "rotor/blade.h"
#include "rotor/family.h"

namespace dynosize {

// The speeds of the entry's tables: tip speeds from kSizedTipSpeedMin to kSizedTipSpeedMax m/s
// (tip Mach 0.12-0.76 at sea level: below, the Reynolds numbers fall under the data's; above,
// compressibility passes the airfoil model's range, rotor/airfoil.h).
inline constexpr double kSizedTipSpeedMin = 40.0;
inline constexpr double kSizedTipSpeedMax = 260.0;

// The range a sized propeller carries: measured/predicted static thrust and torque, p10 and p90
// over the 43 measured propellers of 12 in and more, each left out of its family (CheckSizeOnly;
// docs/validation.md, "A propeller from its size alone"; tests/rotor/family_test.cc recomputes them).
inline constexpr double kSizedThrustRatioP10 = 0.903, kSizedThrustRatioP90 = 1.245;
inline constexpr double kSizedTorqueRatioP10 = 0.914, kSizedTorqueRatioP90 = 1.270;

// The catalog JSON of the sized propeller: id "sized_<family>_<D>x<P>x<B>", static_table and
// j_tables computed. Throws UsageError for an unknown family or a size out of range.
Json SizedPropJson(const PropSize& size);
// Same with the family given (the leave-out check builds families without a propeller).
Json SizedPropJson(const PropSize& size, const RotorFamily& family);

// The catalog propeller entry of a blade run through the blade-element model with the UIUC polar:
// static_table (tip speeds kSizedTipSpeedMin-Max) and j_tables (three tip speeds), without
// "source" (the callers say where the blade comes from).
Json BemtPropJson(const BladeGeometry& blade, const std::string& id, const std::string& name, double pitch_m);
// The entry of a propeller from its own geometry (an APC PE0 file, importers/blade_geometry.h):
// tier estimated, its source the geometry file (`dynosize rotor entry`).
Json GeometryPropJson(const BladeGeometry& blade, const std::string& id, const std::string& geometry_file);

// The check of docs/validation.md ("A propeller from its size alone"): every measured propeller
// of `measured` with a static table and a diameter >= min_diameter_m, predicted from its
// diameter, pitch and blades alone through its default family (DefaultFamilyId), the family
// derived from the data without that propeller's own blade (importers/blade_geometry.h,
// DeriveBundledFamilies). Ratios measured/predicted of the static thrust and torque at each
// measured speed (the same air: the coefficients' ratio).
struct SizeOnlyPoint {
  std::string prop_id, family;
  double diameter_in = 0.0, rpm = 0.0;
  double thrust_ratio = 0.0, torque_ratio = 0.0;  // measured / predicted
};
struct SizeOnlyCheck {
  std::vector<SizeOnlyPoint> points;
  int props = 0;
  double thrust_median = 0.0, torque_median = 0.0;  // median |predicted/measured - 1| over propellers
  // p10 and p90 of the ratios over all points: the range a sized propeller's result carries.
  double thrust_p10 = 0.0, thrust_p90 = 0.0, torque_p10 = 0.0, torque_p90 = 0.0;
  // Share of each propeller's points inside the p10-p90 of the OTHER propellers' ratios.
  double thrust_coverage = 0.0, torque_coverage = 0.0;
};
SizeOnlyCheck CheckSizeOnly(const std::vector<PropEntry>& measured, const std::string& shared_data_dir,
                            double min_diameter_m);

}  // namespace dynosize
