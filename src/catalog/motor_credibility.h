// Motor credibility: the motor constant of a catalog motor checked against the other windings
// of the same frame.
//
// Motor constant (DC circuit, catalog/conventions.h): Km = KT_dc/sqrt(R_dc) [N*m/sqrt(W)], with
// KT_dc = 60/(2*pi*Kv): the torque per square root of copper-loss watt. For one frame (same
// laminations, magnets and slot area) it does not depend on the winding: N turns give KT ~ N and,
// at the same copper fill, R ~ N^2, so KT^2/R is the same (standard motor-design result, e.g.
// Hendershot & Miller, "Design of Brushless Permanent-Magnet Machines", ch. 1; Drela's QPROP
// motor notes). Real windings differ by their fill factor, a few tens of percent.
//
// A catalog entry whose Km is more than kFamilyKmRatioMax times the median of its frame family
// (the entries whose names differ only in the winding token: "AXI 2212-12", "AXI 2212-20", ...,
// at least kFamilyMinMembers of them) has a resistance that no winding of that frame can have:
// typically a misplaced decimal or a value in the wrong unit. Such a motor would look several
// times more efficient than it is and win every search, so the importers exclude it by default
// (EntryBase::exclude_reason) and say why. Example: DriveCalc's AXI 2212-34 stores R = 0.051 ohm,
// Km 2.6x its family's median; a fit of DriveCalc's own measurements of that motor gives
// R_dc = 0.31 ohm (catalog/drivecalc_fitted.json, dc_m_56_fit).
//
// Second rule, for motors without a family (user-contributed entries only): Km against the
// motor's mass. Over DriveCalc's motors of 10 g to 2 kg (1,583 with Kv, R and mass; least squares
// on log Km vs log m, refitted 5 times without points beyond 2.5 robust sd) the typical motor
// constant is Km = exp(-1.4003)*m[kg]^0.8511 N*m/sqrt(W), robust log scatter 0.375 (Km grows
// with the active volume). An entry above kMassKmRatioMax times that (log residual 1.39, 3.7
// robust sd) has 16x less copper loss per torque^2 than a typical motor of its mass: a
// resistance a decade too small (mOhm typed as ohm/10, ...) looks like this. Excluded by default
// like the family outliers. tests/catalog/motor_credibility_test.cc recomputes the law.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace dynosize {

inline constexpr double kFamilyKmRatioMax = 2.0;
inline constexpr std::size_t kFamilyMinMembers = 3;

inline constexpr double kMassKmLawLogA = -1.4003;
inline constexpr double kMassKmLawExponent = 0.8511;
inline constexpr double kMassKmRatioMax = 4.0;
inline constexpr double kMassKmLawMinKg = 0.010;
inline constexpr double kMassKmLawMaxKg = 2.0;

// The typical Km of a motor of this mass (the law above).
double TypicalMotorConstantForMass(double mass_kg);

// Third rule, for geared entries (gear_ratio > 1): the Kv must be the motor's, not the output
// shaft's. A Kv measured at the output is the motor's divided by the ratio N, which makes Km
// (~ 1/Kv) N times too large. A geared unit's Km from the motor's own Kv is at most a typical
// direct-drive motor's of the same mass (its mass holds the gearbox too): on DriveCalc's
// geared entries with a mass and a resistance it is 0.17-1.12 x the mass law (median 0.31)
// with Kv = N x DriveCalc's kV (the motor's, docs/model.md section 12), and 0.83-4.9 x (median
// 1.70) with DriveCalc's kV itself (the output shaft's). An entry above kGearedKmRatioMax x
// the law is refused by Catalog::Load and `catalog validate` (its Kv reads as the output
// shaft's). Applies to entries of 10 g to 2 kg with kv_rpm_per_v, a resistance and a mass.
inline constexpr double kGearedKmRatioMax = 1.2;
// Km(kv, r_dc) over the typical Km of the mass; 0 when the rule does not apply.
double GearedKmRatio(double kv_rpm_per_v, double r_dc_ohm, double mass_kg);

// Km = KT_dc/sqrt(R_dc), KT_dc = 60/(2*pi*Kv); 0 when Kv or R_dc is not positive.
double MotorConstantDc(double kv_rpm_per_v, double r_dc_ohm);

// The frame family of a motor name: the name without a gear suffix ("/6.7:1"), text in
// parentheses and the last "-" or "/" winding token (its trailing letters kept, since they
// often name the stack length: Hacker "A30-28S" and "A30-28L" are different frames), lower case;
// "" when the name has no winding token.
std::string FrameFamily(const std::string& name);

struct MotorKmInput {
  std::string name;
  double kv_rpm_per_v = 0.0;
  double r_dc_ohm = 0.0;
  double mass_kg = 0.0;             // 0: unknown
  bool user_contributed = false;    // the mass rule applies to user-contributed entries only
};

struct FamilyOutlier {
  std::size_t index = 0;  // into the input
  std::string family;     // "" for the mass rule
  std::size_t members = 0;
  double km = 0.0;
  double family_median_km = 0.0;
  double ratio = 0.0;  // km / family_median_km
};

// The entries whose Km exceeds kFamilyKmRatioMax x the median of their frame family (families
// of at least kFamilyMinMembers entries), in input order.
std::vector<FamilyOutlier> FrameFamilyOutliers(const std::vector<MotorKmInput>& motors);

// The user-contributed entries of 10 g to 2 kg whose Km exceeds kMassKmRatioMax x the typical
// Km of their mass, in input order (family_median_km holds the typical value, members 0).
std::vector<FamilyOutlier> MassLawOutliers(const std::vector<MotorKmInput>& motors);

// Both rules: the family outliers, then the mass-law outliers not already among them, in input
// order. This is what the importers exclude.
std::vector<FamilyOutlier> ImplausibleMotorConstants(const std::vector<MotorKmInput>& motors);

// One line for the entry's exclude key and note.
std::string FamilyOutlierReason(const FamilyOutlier& o);

}  // namespace dynosize
