// Heavy-lift multirotor motors (shared/data/heavy_lift_motors, README there): KDE Direct's
// datasheet tables of 21 motors (kde_datasheets.csv, kdedirect.com as scraped by
// CWRU-VTOL/MotorDatabase) and the symbench corpus rows of T-Motor and of the KDE motors that
// table does not hold (heavy_lift_motors.csv). Every value is the maker's: Kv, the DC-circuit
// resistance, the no-load current at 10 V, continuous (180 s) and peak ratings, cells and mass.
#include <cmath>
#include <set>

#include "catalog/conventions.h"
#include "common/units.h"
#include "importers/csv.h"
#include "importers/importers.h"

namespace dynosize {

namespace {

constexpr const char* kKdeDataset = "KDE Direct datasheets (kdedirect.com, via CWRU-VTOL/MotorDatabase)";
constexpr const char* kCorpusDataset = "symbench/uav-analysis corpus (heavy-lift motors)";

using Cells = CsvCells;

// The constants every BLDC entry of this folder states: Kv, the DC resistance and Io at the
// test voltage (conventions.h 1.: rm_ohm = 0.7492*R_dc, io_a = Io_dc/1.1095).
void SetStatedConstants(EntryBuilder* b, double kv, double r_dc_ohm, double io_dc_a, double io_v) {
  b->Set("type", "bldc", "derived");
  b->SetNum("kv_rpm_per_v", kv, "datasheet");
  SetResistanceFromDc(b, r_dc_ohm, "datasheet");
  b->SetNum("io_a", RmsNoLoadCurrentFromDc(io_dc_a), "derived", 4);
  b->SetNum("io_test_voltage_v", io_v, "datasheet");
}

void ImportKdeDatasheets(const std::string& dir, ImportedDataset* out, std::set<std::string>* names) {
  const std::string file = "kde_datasheets.csv";
  const CsvTable t = ReadCsv(dir + "/" + file);
  for (const auto& r : t.rows) {
    const Cells c{&t, &r};
    const std::string name = CleanName(c.Str("motor"));
    const std::string ex = file + ":" + std::to_string(r.line) + " " + name;
    const auto kv = c.Pos("kv_rpm_per_v"), rm = c.Pos("rm_ohm"), io = c.Pos("io_a"),
               io_v = c.Pos("io_test_v");
    if (!kv || !rm || !io || !io_v) {
      out->report.Drop("motors", "Kv, R or Io not stated", ex);
      continue;
    }
    EntryBuilder b("hl_m_" + Slug(name), name);
    SetStatedConstants(&b, *kv, *rm, *io, *io_v);
    // The flying mass: KDE prints it without and with the wires and bullets.
    if (const auto m = c.Pos("mass_with_wires_kg")) b.SetNum("mass_kg", *m, "datasheet");
    else if (const auto m0 = c.Pos("mass_kg")) b.SetNum("mass_kg", *m0, "datasheet");
    if (const auto i = c.Pos("i_max_a")) b.SetNum("max_current_a", *i, "datasheet");
    if (const auto p = c.Pos("p_max_w")) b.SetNum("max_power_w", *p, "datasheet");
    if (const auto v = c.Pos("v_max_v")) b.SetNum("vdc_max_v", *v, "datasheet");
    if (const auto n = c.Pos("cells_min")) b.Set("cells_min", static_cast<int>(*n), "datasheet");
    if (const auto n = c.Pos("cells_max")) b.Set("cells_max", static_cast<int>(*n), "datasheet");
    if (const auto pp = c.Pos("pole_pairs")) b.Set("poles", static_cast<int>(2 * *pp), "datasheet");
    b.Source(kKdeDataset, file + " line " + std::to_string(r.line),
             "KDE's table: Kv, R (the DC circuit's, rm_dc_ohm), Io at " + c.Str("io_test_v") +
                 " V; 'maximum continuous' current and power are KDE's 180 s ratings; mass with "
                 "wires and bullets; the KDE in-system law applies (docs/in-system-law.md)");
    b.Tier("manufacturer_stated");
    out->motors.push_back(b.Build());
    out->report.Keep("motors");
    names->insert(name);
  }
}

// T-Motor rows and the KDE rows of the corpus that kde_datasheets.csv does not hold (KDE's G3
// 600XF/700XF, with peak ratings from the corpus's demo1 table).
void ImportCorpusMotors(const std::string& dir, ImportedDataset* out,
                        const std::set<std::string>& kde_names) {
  const std::string file = "heavy_lift_motors.csv";
  const CsvTable t = ReadCsv(dir + "/" + file);
  for (const auto& r : t.rows) {
    const Cells c{&t, &r};
    const std::string maker = CleanName(c.Str("maker")), model = CleanName(c.Str("model"));
    const std::string name = model.rfind("KDE", 0) == 0 ? model : maker + " " + model;
    const std::string ex = file + ":" + std::to_string(r.line) + " " + name;
    if (kde_names.count(model)) {
      out->report.Drop("motors", "also in kde_datasheets.csv (KDE's own table used)", ex);
      continue;
    }
    const auto kv = c.Pos("kv_rpm_per_v"), rm = c.Pos("r_ohm"), io = c.Pos("io_a"),
               io_v = c.Pos("io_test_v");
    if (!kv || !rm || !io || !io_v) {
      out->report.Drop("motors", "Kv, R or Io not stated", ex);
      continue;
    }
    EntryBuilder b("hl_m_" + Slug(name), name);
    SetStatedConstants(&b, *kv, *rm, *io, *io_v);
    if (const auto m = c.Pos("mass_kg")) b.SetNum("mass_kg", *m, "datasheet");
    if (const auto i = c.Pos("i_max_a")) b.SetNum("max_current_a", *i, "datasheet");
    if (const auto p = c.Pos("p_max_w")) b.SetNum("max_power_w", *p, "datasheet");
    if (const auto i = c.Pos("i_peak_a")) b.SetNum("peak_current_a", *i, "datasheet");
    if (const auto p = c.Pos("p_peak_w")) b.SetNum("peak_power_w", *p, "datasheet");
    if (const auto n = c.Pos("cells_min")) b.Set("cells_min", static_cast<int>(*n), "datasheet");
    if (const auto n = c.Pos("cells_max")) b.Set("cells_max", static_cast<int>(*n), "datasheet");
    b.Source(kCorpusDataset, file + " line " + std::to_string(r.line) + " (" +
                                 c.Str("symbench_model") + ")",
             "the maker's catalogue values as the corpus holds them (R: INTERNAL_RESISTANCE, "
             "basis not stated, taken as the DC circuit's; Io at 10 V); peak ratings without a "
             "stated duration");
    b.Tier("manufacturer_stated");
    out->motors.push_back(b.Build());
    out->report.Keep("motors");
  }
}

}  // namespace

ImportedDataset ImportHeavyLiftMotors(const std::string& dir) {
  ImportedDataset out;
  out.report.dataset = "heavy_lift_motors";
  out.report.output_file = "heavy_lift_motors.json";
  out.comment =
      "Generated by dynosize ImportAll from shared/data/heavy_lift_motors: KDE Direct's "
      "datasheet tables of 21 motors (kdedirect.com, scraped 2024-12-31 by CWRU-VTOL/"
      "MotorDatabase commit 5103935, MIT) and the symbench/uav-analysis corpus (commit 3249eff, "
      "GPL-3.0) rows of T-Motor and of KDE's G3 motors: the makers' values. rm_ohm = 0.7492 x the "
      "stated resistance (rm_dc_ohm, catalog/conventions.h), io_a = Io(10 V)/1.1095 (eq 56). "
      "Corpus rows of KDE motors that KDE's own table holds are left out. Do not edit by hand.";
  std::set<std::string> kde_names;
  ImportKdeDatasheets(dir, &out, &kde_names);
  ImportCorpusMotors(dir, &out, kde_names);
  return out;
}

}  // namespace dynosize
