// FAST-UAV component catalogues (shared/data/fastuav_catalogues, ';'-separated): motors, ESCs,
// LiPo packs and APC multirotor propellers, from manufacturer spec sheets (not measured by the
// FAST-UAV authors; APC coefficients are APC's computed values).
#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "catalog/esc_prior.h"
#include "common/units.h"
#include "importers/csv.h"
#include "importers/importers.h"

namespace dynosize {

namespace {

constexpr const char* kDataset = "FAST-UAV catalogues (SizingLab)";

struct Row {
  const CsvTable* t;
  const CsvRow* r;
  std::string file;
  std::string Str(const char* col) const { return t->Field(*r, t->Column(col)); }
  std::optional<double> Num(const char* col) const { return ParseNumber(Str(col)); }
  std::string Where() const { return file + ":" + std::to_string(r->line); }
};

// The source lost the diameter sign of Maxon's "EC 4 ø4 mm" to '?': put it back.
std::string RestoreDiameterSign(std::string s) {
  for (std::size_t i = 0; i + 1 < s.size(); ++i) {
    if (s[i] == '?' && std::isdigit(static_cast<unsigned char>(s[i + 1]))) {
      s.replace(i, 1, "\xC3\xB8");
    }
  }
  return s;
}

std::string RowKey(const CsvRow& r) {
  std::string k;
  for (const auto& f : r.fields) k += Trim(f) + "\x1f";
  return k;
}

void ImportMotors(const std::string& dir, ImportedDataset* out) {
  const std::string file = "Motors_Data.csv";
  const CsvTable t = ReadCsv(dir + "/" + file);
  std::map<std::string, int> name_count;
  for (const auto& r : t.rows) ++name_count[CleanName(t.Field(r, t.Column("Model")))];
  std::set<std::string> seen;
  std::size_t restored = 0, stray_marks = 0;
  for (std::size_t k = 0; k < t.rows.size(); ++k) {
    const Row row{&t, &t.rows[k], file};
    const std::string raw = CleanName(row.Str("Model"));
    std::string name = RestoreDiameterSign(raw);
    if (name != raw) ++restored;
    // 41 Scorpion names start with '?': a character lost in the source's encoding.
    if (name.size() > 1 && name[0] == '?' && std::isalpha(static_cast<unsigned char>(name[1]))) {
      name.erase(0, 1);
      ++stray_marks;
    }
    const std::string ex = row.Where() + " " + name;
    if (!seen.insert(RowKey(*row.r)).second) {
      out->report.Drop("motors", "exact duplicate row", ex);
      continue;
    }
    const auto kv = row.Num("Kv_rpm_v"), io = row.Num("Io_A"), rm = row.Num("R_ohm"),
               mass = row.Num("Mass_g"), imax = row.Num("Imax_A"), ns = row.Num("No_s"),
               volt = row.Num("Voltage"), poles = row.Num("Pole_number");
    if (!kv || !(*kv > 0) || !rm || !(*rm > 0) || !io || *io < 0) {
      out->report.Drop("motors", "Kv, R or Io missing or zero", ex);
      continue;
    }
    if (name_count[raw] > 1) {
      char buf[48];
      std::snprintf(buf, sizeof buf, " (%g Kv)", *kv);
      name += buf;
    }
    EntryBuilder b("fu_m_" + std::to_string(k + 1), name);
    b.Set("type", "bldc", "derived");
    b.SetNum("kv_rpm_per_v", *kv, "datasheet");
    SetResistanceFromDc(&b, *rm, "datasheet");
    // Datasheet Io is a DC (battery) current at no load and full throttle; the model's io_a is
    // an rms phase current: eq (56) at TR = 1 gives IDC = 1.1095*Irms.
    b.SetNum("io_a", *io / kIdealIdcPerIrmsPerThrottle, "derived", 4);
    if (volt && *volt > 0) {
      b.SetNum("io_test_voltage_v", *volt, "assumed");
      b.SetNum("vdc_nominal_v", *volt, "datasheet");
    }
    if (imax && *imax > 0) b.SetNum("max_current_a", *imax, "datasheet");
    if (mass && *mass > 0) b.SetNum("mass_kg", GramsToKg(*mass), "datasheet");
    const std::string rating_note = SetRatingOrExclude(
        &b, imax && *imax > 0, mass && *mass > 0 ? std::optional<double>(GramsToKg(*mass)) : std::nullopt,
        false);
    if (ns && *ns >= 1) b.Set("cells_max", static_cast<int>(*ns), "datasheet");
    if (poles && *poles >= 2) b.Set("poles", static_cast<int>(*poles), "datasheet");
    b.Source(kDataset, file + " row " + std::to_string(k + 1) + " (" + row.Str("TYPE") + ")",
             "io_a = datasheet Io (DC) / 1.1095 (eq 56); rm_ohm = 0.7492 x datasheet R (DC "
             "circuit, catalog/conventions.h); Io test voltage assumed = the Voltage column "
             "(FAST-UAV README)" + rating_note);
    b.Tier("manufacturer_stated");
    out->motors.push_back(b.Build());
    out->report.Keep("motors");
  }
  if (restored) {
    out->report.notes.push_back(file + ": " + std::to_string(restored) +
                                " names with '?' for the diameter sign restored to '\xC3\xB8'");
  }
  if (stray_marks) {
    out->report.notes.push_back(file + ": " + std::to_string(stray_marks) +
                                " names with a leading '?' (a character lost in the source) cleaned");
  }
  out->report.notes.push_back("Non-Dominated-Motors.csv and Non-Dominated-ESC.csv not imported: "
                              "Pareto subsets of Motors_Data.csv and ESC_data.csv");
}

void ImportEscs(const std::string& dir, ImportedDataset* out) {
  const std::string file = "ESC_data.csv";
  const CsvTable t = ReadCsv(dir + "/" + file);
  const EscPrior& prior = DefaultEscPrior();
  std::map<std::string, int> name_count;
  for (const auto& r : t.rows) ++name_count[CleanName(t.Field(r, t.Column("Model")))];
  std::set<std::string> seen;
  for (std::size_t k = 0; k < t.rows.size(); ++k) {
    const Row row{&t, &t.rows[k], file};
    std::string name = CleanName(row.Str("Model"));
    const std::string ex = row.Where() + " " + name;
    if (!seen.insert(RowKey(*row.r)).second) {
      out->report.Drop("escs", "exact duplicate row", ex);
      continue;
    }
    const auto imax = row.Num("I_max_A"), mass = row.Num("Mass_g"), vmax = row.Num("V_max_V"),
               pmax = row.Num("Power_max_W");
    if (!imax || !(*imax > 0)) {
      out->report.Drop("escs", "no current rating", ex);
      continue;
    }
    if (name_count[name] > 1) {
      char buf[32];
      std::snprintf(buf, sizeof buf, " %gA", *imax);
      name += buf;
    }
    EntryBuilder b("fu_e_" + std::to_string(k + 1), name);
    b.SetNum("resc_ohm", PriorEscResistanceOhm(*imax), "assumed", 3);
    b.SetNum("c1", prior.c1, "assumed");
    b.SetNum("c0", prior.c0, "assumed");
    b.SetNum("tr_sat", prior.tr_sat, "assumed");
    b.SetNum("sat_slope", prior.sat_slope, "assumed");
    b.SetNum("max_current_a", *imax, "datasheet");
    if (vmax && *vmax > 0) b.SetNum("vdc_max_v", *vmax, "datasheet");
    if (mass && *mass > 0) b.SetNum("mass_kg", GramsToKg(*mass), "datasheet");
    if (pmax && *pmax > 0) b.SetNum("max_power_w", *pmax, "datasheet");
    b.Source(kDataset, file + " row " + std::to_string(k + 1) + " (" + row.Str("TYPE") + ")",
             "no resistance in the source: resc_ohm from the Imax prior; c1, c0, tr_sat, "
             "sat_slope: esc_prior.h");
    b.Tier("manufacturer_stated");
    out->escs.push_back(b.Build());
    out->report.Keep("escs");
  }
}

void ImportBatteries(const std::string& dir, ImportedDataset* out) {
  const std::string file = "Non-Dominated-Augmented-Batteries.csv";
  const CsvTable t = ReadCsv(dir + "/" + file);
  // A row is a real pack (n_series = n_parallel = 1) or an "augmented" combination of one. A
  // model that appears only in combinations is recovered from its smallest combination by
  // dividing voltage by n_series, capacity and current by n_parallel, mass by both.
  struct Pick {
    std::size_t row = 0;
    double ns = 0, np = 0;
  };
  std::map<std::string, Pick> pick;
  std::vector<std::string> order;
  for (std::size_t k = 0; k < t.rows.size(); ++k) {
    const Row row{&t, &t.rows[k], file};
    const std::string name = CleanName(row.Str("Model"));
    const auto ns = row.Num("n_series"), np = row.Num("n_parallel");
    if (!ns || !np || *ns < 1 || *np < 1) {
      out->report.Drop("batteries", "n_series or n_parallel missing", row.Where() + " " + name);
      continue;
    }
    auto it = pick.find(name);
    if (it == pick.end()) {
      pick[name] = {k, *ns, *np};
      order.push_back(name);
    } else if (*ns * *np < it->second.ns * it->second.np) {
      it->second = {k, *ns, *np};
    }
  }
  for (std::size_t k = 0; k < t.rows.size(); ++k) {
    const Row row{&t, &t.rows[k], file};
    const std::string name = CleanName(row.Str("Model"));
    const auto p = pick.find(name);
    if (p != pick.end() && p->second.row != k) {
      out->report.Drop("batteries",
                       "augmented series/parallel combination of a pack (not a product; build "
                       "packs with PackFromEntry)",
                       row.Where() + " " + name);
    }
  }
  for (const std::string& name : order) {
    const Pick& pk = pick[name];
    const Row row{&t, &t.rows[pk.row], file};
    const std::string ex = row.Where() + " " + name;
    const auto v = row.Num("Voltage_V"), cap = row.Num("Capacity_mAh"), imax = row.Num("Imax_A"),
               c_burst = row.Num("Max_Burst_Discharge_Rate_C"), mass = row.Num("Weight_kg");
    if (!v || !cap || !(*v > 0) || !(*cap > 0)) {
      out->report.Drop("batteries", "no voltage or capacity", ex);
      continue;
    }
    const bool recovered = pk.ns != 1 || pk.np != 1;
    const char* how = recovered ? "derived" : "datasheet";
    const double unit_v = *v / pk.ns, unit_cap_mah = *cap / pk.np;
    // LiPo packs: 3.7 V nominal per cell.
    const int cells = std::max(1, static_cast<int>(std::lround(unit_v / 3.7)));
    EntryBuilder b("fu_b_" + Slug(name), name);
    b.Set("chemistry", "lipo", "datasheet");
    b.Set("cells_series", cells, "derived");
    b.SetNum("capacity_ah", MahToAh(unit_cap_mah), how);
    b.SetNum("voltage_nominal_v", unit_v, how);
    if (imax && *imax > 0) b.SetNum("max_current_a", *imax / pk.np, how);
    if (c_burst && *c_burst > 0) {
      b.SetNum("peak_current_a", *c_burst * MahToAh(unit_cap_mah), "derived");
    }
    if (mass && *mass > 0) b.SetNum("mass_kg", *mass / (pk.ns * pk.np), how);
    std::string note = "cells_series = voltage/3.7 V; peak current = burst C rate x capacity; "
                       "no internal resistance in the source";
    if (recovered) {
      char buf[96];
      std::snprintf(buf, sizeof buf, "; only in the data as a %gS%gP combination, divided back",
                    pk.ns, pk.np);
      note += buf;
    }
    b.Source(kDataset, file + " line " + std::to_string(row.r->line) + " (" + row.Str("TYPE") + ")",
             note);
    b.Tier("manufacturer_stated");
    out->batteries.push_back(b.Build());
    out->report.Keep("batteries");
  }
}

void ImportProps(const std::string& dir, ImportedDataset* out) {
  const std::string file = "APC_propellers_MR.csv";
  const CsvTable t = ReadCsv(dir + "/" + file);
  std::set<std::string> ids;
  for (std::size_t k = 0; k < t.rows.size(); ++k) {
    const Row row{&t, &t.rows[k], file};
    const std::string name = CleanName(row.Str("Product Name"));
    const std::string ex = row.Where() + " " + name;
    const auto d_in = row.Num("Diameter (INCHES)"), p_in = row.Num("Pitch (INCHES)"),
               mass_g = row.Num("Weight (grams)"), ct = row.Num("Ct_static"),
               cp = row.Num("Cp_static");
    if (!d_in || !(*d_in > 0) || !ct || !cp || !(*ct > 0) || !(*cp > 0)) {
      out->report.Drop("props", "no diameter or static coefficients", ex);
      continue;
    }
    const std::string id = "fu_p_apc_" + Slug(name);
    if (!ids.insert(id).second) {
      out->report.Drop("props", "duplicate product", ex);
      continue;
    }
    EntryBuilder b(id, "APC " + name + " (multirotor)");
    b.SetNum("diameter_m", InchToMeter(*d_in), "datasheet");
    if (p_in && *p_in > 0) b.SetNum("pitch_m", InchToMeter(*p_in), "datasheet");
    b.Set("blades", 2, "assumed");
    if (mass_g && *mass_g > 0) b.SetNum("mass_kg", GramsToKg(*mass_g), "datasheet");
    b.SetNum("ct_static", *ct, "computed");
    b.SetNum("cp_static", *cp, "computed");
    b.Source(kDataset, file + " line " + std::to_string(row.r->line) + " (SKU " +
                           row.Str("Product Code (SKU)") + ")",
             "APC's computed static coefficients, no rpm dependence, no forward flight");
    b.Tier("manufacturer_computed");
    KeepAuditedProp(b.Build(), ex, out);
  }
  out->report.notes.push_back("Propeller_Data.csv not imported: generic APC MR CT/CP vs J by "
                              "pitch ratio, not tied to a product");
}

}  // namespace

ImportedDataset ImportFastUav(const std::string& dir) {
  ImportedDataset out;
  out.report.dataset = "fastuav_catalogues";
  out.report.output_file = "fastuav.json";
  out.comment =
      "Generated by dynosize ImportAll from shared/data/fastuav_catalogues: FAST-UAV component "
      "catalogues (github.com/SizingLab/FAST-UAV commit 421083d, GPL-3.0-only), compiled from "
      "manufacturer spec sheets (not measured). Motors: io_a = datasheet Io / 1.1095 (rms, "
      "eq 56); rm_ohm = 0.7492 x the datasheet resistance (the DC circuit's; catalog/conventions.h), "
      "which rm_dc_ohm keeps. ESCs have no resistance: resc_ohm and c1, c0, tr_sat, sat_slope are the "
      "esc_prior.h prior (assumed). Batteries: the real packs (n_series = n_parallel = 1), not "
      "the augmented combinations (two models found only as combinations are divided back). "
      "APC MR props: APC's computed static CT, CP. Do not edit "
      "by hand.";
  ImportMotors(dir, &out);
  ImportEscs(dir, &out);
  ImportBatteries(dir, &out);
  ImportProps(dir, &out);
  return out;
}

}  // namespace dynosize
