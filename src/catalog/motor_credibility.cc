#include "catalog/motor_credibility.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <map>
#include <regex>

#include "common/units.h"

namespace dynosize {

double GearedKmRatio(double kv_rpm_per_v, double r_dc_ohm, double mass_kg) {
  if (!(mass_kg >= kMassKmLawMinKg && mass_kg <= kMassKmLawMaxKg)) return 0.0;
  return MotorConstantDc(kv_rpm_per_v, r_dc_ohm) / TypicalMotorConstantForMass(mass_kg);
}

double MotorConstantDc(double kv_rpm_per_v, double r_dc_ohm) {
  if (!(kv_rpm_per_v > 0.0) || !(r_dc_ohm > 0.0)) return 0.0;
  const double kt_dc = 1.0 / RpmToRadPerSec(kv_rpm_per_v);  // V*s/rad = N*m/A (DC machine)
  return kt_dc / std::sqrt(r_dc_ohm);
}

double TypicalMotorConstantForMass(double mass_kg) {
  return mass_kg > 0.0 ? std::exp(kMassKmLawLogA) * std::pow(mass_kg, kMassKmLawExponent) : 0.0;
}

std::string FrameFamily(const std::string& name) {
  static const std::regex kGear(R"(\s*[/-]?\s*\d+(\.\d+)?\s*:\s*1.*$)");
  static const std::regex kParen(R"(\s*\([^)]*\))");
  static const std::regex kWinding(R"(^(.*\d.*?)\s*[-/]\s*([^-/\s]*\d[^-/\s]*)$)");
  std::string n = std::regex_replace(name, kGear, "");
  n = std::regex_replace(n, kParen, "");
  while (!n.empty() && std::isspace(static_cast<unsigned char>(n.back()))) n.pop_back();
  std::smatch m;
  if (!std::regex_match(n, m, kWinding)) return "";
  std::string family = m[1].str();
  const std::string token = m[2].str();
  std::size_t k = token.size();
  while (k > 0 && std::isalpha(static_cast<unsigned char>(token[k - 1]))) --k;
  if (k < token.size()) family += " " + token.substr(k);
  std::transform(family.begin(), family.end(), family.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return family;
}

std::vector<FamilyOutlier> FrameFamilyOutliers(const std::vector<MotorKmInput>& motors) {
  std::map<std::string, std::vector<std::size_t>> families;
  std::vector<double> km(motors.size(), 0.0);
  for (std::size_t i = 0; i < motors.size(); ++i) {
    km[i] = MotorConstantDc(motors[i].kv_rpm_per_v, motors[i].r_dc_ohm);
    const std::string f = FrameFamily(motors[i].name);
    if (!f.empty() && km[i] > 0.0) families[f].push_back(i);
  }
  std::vector<FamilyOutlier> out;
  for (const auto& [family, members] : families) {
    if (members.size() < kFamilyMinMembers) continue;
    std::vector<double> v;
    for (std::size_t i : members) v.push_back(km[i]);
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    const double median = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
    for (std::size_t i : members) {
      if (km[i] > kFamilyKmRatioMax * median) {
        out.push_back({i, family, members.size(), km[i], median, km[i] / median});
      }
    }
  }
  std::sort(out.begin(), out.end(), [](const FamilyOutlier& a, const FamilyOutlier& b) { return a.index < b.index; });
  return out;
}

std::vector<FamilyOutlier> MassLawOutliers(const std::vector<MotorKmInput>& motors) {
  std::vector<FamilyOutlier> out;
  for (std::size_t i = 0; i < motors.size(); ++i) {
    const MotorKmInput& m = motors[i];
    if (!m.user_contributed || m.mass_kg < kMassKmLawMinKg || m.mass_kg > kMassKmLawMaxKg) continue;
    const double km = MotorConstantDc(m.kv_rpm_per_v, m.r_dc_ohm), typical = TypicalMotorConstantForMass(m.mass_kg);
    if (km > kMassKmRatioMax * typical) out.push_back({i, "", 0, km, typical, km / typical});
  }
  return out;
}

std::vector<FamilyOutlier> ImplausibleMotorConstants(const std::vector<MotorKmInput>& motors) {
  std::vector<FamilyOutlier> out = FrameFamilyOutliers(motors);
  for (const FamilyOutlier& o : MassLawOutliers(motors)) {
    const bool seen = std::any_of(out.begin(), out.end(), [&](const FamilyOutlier& f) { return f.index == o.index; });
    if (!seen) out.push_back(o);
  }
  std::sort(out.begin(), out.end(), [](const FamilyOutlier& a, const FamilyOutlier& b) { return a.index < b.index; });
  return out;
}

std::string FamilyOutlierReason(const FamilyOutlier& o) {
  char buf[320];
  if (o.family.empty()) {
    std::snprintf(buf, sizeof buf,
                  "motor constant KT/sqrt(R) = %.3g N*m/sqrt(W) is %.2gx the typical %.3g of motors of "
                  "its mass: R is likely a decade too small (catalog/motor_credibility.h)",
                  o.km, o.ratio, o.family_median_km);
    return buf;
  }
  std::snprintf(buf, sizeof buf,
                "motor constant KT/sqrt(R) = %.3g N*m/sqrt(W) is %.2gx the median (%.3g) of the %zu "
                "windings of its frame '%s': no winding of one frame differs that much, so R is "
                "likely wrong (catalog/motor_credibility.h)",
                o.km, o.ratio, o.family_median_km, o.members, o.family.c_str());
  return buf;
}

}  // namespace dynosize
