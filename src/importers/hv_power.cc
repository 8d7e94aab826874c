// High-voltage power electronics and energy storage for heavy-lift and eVTOL sizing:
// shared/data/hv_controllers (motor controllers and ESCs for 12S and more, up to 800 V) and
// shared/data/packs_and_cells (12S-14S LiPo packs and 18650/21700 Li-ion cells). READMEs there.
#include <cmath>
#include <cstdio>

#include "catalog/esc_prior.h"
#include "common/units.h"
#include "importers/csv.h"
#include "importers/importers.h"

namespace dynosize {

namespace {

constexpr const char* kControllersDataset =
    "MCEVS controller survey and maker documents (hv_controllers)";
constexpr const char* kPacksDataset = "heavy-lift packs and Li-ion cells (packs_and_cells)";

// The inverter efficiency at the continuous rating assumed where a controller states none: the
// lowest any inverter of the data states (BRUSA DMC5, 97 %; magniDrive and BRUSA BDC state
// 98.9 %), so that a controller without a figure is not made better than the stated ones.
constexpr double kAssumedInverterEfficiency = 0.97;

struct Cells {
  const CsvTable* t;
  const CsvRow* r;
  std::string Str(const char* col) const { return t->Field(*r, t->Column(col)); }
  std::optional<double> Pos(const char* col) const {
    const auto v = ParseNumber(Str(col));
    return v && *v > 0 ? v : std::nullopt;
  }
};

bool Contains(const std::string& text, const char* what) { return text.find(what) != std::string::npos; }

// Why a controller row is not a motor controller the model can pair with a motor, or "".
std::string NotAMotorController(const Cells& c) {
  const std::string type = c.Str("device_type");
  if (Contains(type, "DC/DC")) return "a DC/DC converter, not a motor inverter";
  if (Contains(type, "generator") || Contains(type, "hybrid")) {
    return "a generator or hybrid-system controller, not a motor inverter";
  }
  return "";
}

// eq (47)'s RESC from a stated (or the assumed) efficiency at the continuous rating: the ESC
// loss of the ideal ESC, PESC = sqrt(27/10)*RESC*Irms^2 (model.md section 10 with C1 = 1.1095,
// C0 = 0), equals (1/eta - 1)*P at P = p_cont_w and Irms = i_cont_a.
double ResistanceFromEfficiencyOhm(double eta, double p_cont_w, double i_cont_a) {
  return (1.0 / eta - 1.0) * p_cont_w / (kPacPerVllIrms * i_cont_a * i_cont_a);
}

void ImportController(const Cells& c, std::size_t line, ImportedDataset* out) {
  const std::string name = CleanName(c.Str("maker") + " " + c.Str("name"));
  const EscPrior& prior = DefaultEscPrior();
  EntryBuilder b("hv_e_" + Slug(name), name);
  const auto i_cont = c.Pos("i_cont_a"), i_peak = c.Pos("i_peak_a"), p_cont = c.Pos("p_cont_kw"),
             eta_pct = c.Pos("efficiency_pct");
  std::string how_r;
  if (i_cont && p_cont) {
    const double eta = eta_pct ? *eta_pct / 100.0 : kAssumedInverterEfficiency;
    b.SetNum("resc_ohm", ResistanceFromEfficiencyOhm(eta, *p_cont * 1e3, *i_cont),
             eta_pct ? "derived" : "assumed", 3);
    how_r = eta_pct ? "resc_ohm from the stated efficiency at the continuous power and current"
                    : "resc_ohm from 97 % efficiency (the lowest an inverter here states) at the "
                      "continuous power and current";
  } else {
    b.SetNum("resc_ohm", PriorEscResistanceOhm(i_cont ? *i_cont : i_peak ? *i_peak : 100.0),
             "assumed", 3);
    how_r = "resc_ohm from the hobby-ESC current prior (esc_prior.h)";
  }
  b.SetNum("c1", prior.c1, "assumed");
  b.SetNum("c0", prior.c0, "assumed");
  b.SetNum("tr_sat", prior.tr_sat, "assumed");
  b.SetNum("sat_slope", prior.sat_slope, "assumed");
  if (i_cont) b.SetNum("max_current_a", *i_cont, "datasheet");
  if (i_peak) b.SetNum("ipeak_a", *i_peak, "datasheet");
  if (const auto d = DurationTextS(c.Str("i_peak_duration")); d && i_peak) {
    b.SetNum("peak_duration_s", *d, "datasheet");
  }
  if (const auto v = c.Pos("v_max_v")) b.SetNum("vdc_max_v", *v, "datasheet");
  if (const auto v = c.Pos("v_min_v")) b.SetNum("vdc_min_v", *v, "datasheet");
  if (const auto n = c.Pos("cells_max_s")) b.Set("cells_max", static_cast<int>(*n), "datasheet");
  if (const auto n = c.Pos("cells_min_s")) b.Set("cells_min", static_cast<int>(*n), "datasheet");
  if (const auto m = c.Pos("mass_kg")) b.SetNum("mass_kg", *m, "datasheet");
  if (p_cont) b.SetNum("max_power_w", *p_cont * 1e3, "datasheet");
  std::string note = how_r + "; c1, c0, tr_sat, sat_slope: esc_prior.h; current basis: " +
                     c.Str("current_basis") + "; mass: " + c.Str("mass_basis");
  if (!i_cont) {
    b.Set("exclude", "no continuous current rating in the source", "");
    note += "; excluded by default: no continuous current rating";
  }
  b.Source(kControllersDataset, "hv_controllers.csv line " + std::to_string(line) + " (" +
                                    c.Str("source_doc") + ")",
           note);
  b.Tier("manufacturer_stated");
  out->escs.push_back(b.Build());
  out->report.Keep("escs");
}

}  // namespace

ImportedDataset ImportHvControllers(const std::string& dir) {
  ImportedDataset out;
  out.report.dataset = "hv_controllers";
  out.report.output_file = "hv_controllers.json";
  out.comment =
      "Generated by dynosize ImportAll from shared/data/hv_controllers: motor controllers and "
      "ESCs for 12S to 800 V from the MCEVS survey (alfiyandyhr/MCEVS commit 27742a0) and the "
      "maker documents stored with it; ratings are the makers'. The model's ESC constants c1, "
      "c0 and the knee are the esc_prior.h prior; resc_ohm from the stated efficiency at the "
      "continuous rating (97 % where none is stated). The FAST-UAV rows of the folder are the "
      "ESCs of fastuav.json and are not repeated. Do not edit by hand.";
  const CsvTable t = ReadCsv(dir + "/hv_controllers.csv");
  for (const auto& r : t.rows) {
    const Cells c{&t, &r};
    const std::string ex = "hv_controllers.csv:" + std::to_string(r.line) + " " + c.Str("name");
    if (Contains(c.Str("source_doc"), "FAST-UAV")) {
      out.report.Drop("escs", "a FAST-UAV ESC, already in fastuav.json", ex);
      continue;
    }
    const std::string why = NotAMotorController(c);
    if (!why.empty()) {
      out.report.Drop("escs", why, ex);
      continue;
    }
    ImportController(c, r.line, &out);
  }
  return out;
}

namespace {

void ImportTattuPacks(const std::string& dir, ImportedDataset* out) {
  const std::string file = "packs_12s_24s.csv";
  const CsvTable t = ReadCsv(dir + "/" + file);
  for (const auto& r : t.rows) {
    const Cells c{&t, &r};
    const std::string name = CleanName(c.Str("maker") + " " + c.Str("model"));
    const std::string ex = file + ":" + std::to_string(r.line) + " " + name;
    if (c.Str("source") != "symbench") {
      out->report.Drop("batteries",
                       "FAST-UAV series/parallel combination of a pack (its base unit is in "
                       "fastuav.json; a mission builds the series/parallel pack)",
                       ex);
      continue;
    }
    const auto s = c.Pos("cells_series"), p = c.Pos("cells_parallel"), cap = c.Pos("capacity_ah"),
               v = c.Pos("v_nom_v");
    if (!s || !cap || !v) {
      out->report.Drop("batteries", "no cell count, capacity or voltage", ex);
      continue;
    }
    EntryBuilder b("pc_b_" + Slug(c.Str("model")), name);
    b.Set("chemistry", "lipo", "datasheet");
    b.Set("cells_series", static_cast<int>(*s), "datasheet");
    if (p && *p > 1) b.Set("cells_parallel", static_cast<int>(*p), "datasheet");
    b.SetNum("capacity_ah", *cap, "datasheet");
    b.SetNum("voltage_nominal_v", *v, "datasheet");
    if (const auto i = c.Pos("i_cont_a")) b.SetNum("max_current_a", *i, "derived");
    if (const auto i = c.Pos("i_peak_a")) b.SetNum("peak_current_a", *i, "derived");
    if (const auto m = c.Pos("mass_kg")) b.SetNum("mass_kg", *m, "datasheet");
    b.Source(kPacksDataset, file + " line " + std::to_string(r.line) + " (symbench BatteryAll.csv)",
             "currents = the stated C rates x capacity; the source's pack resistance is a "
             "placeholder (12 on every row), not used");
    b.Tier("manufacturer_stated");
    out->batteries.push_back(b.Build());
    out->report.Keep("batteries");
  }
}

void ImportLiIonCells(const std::string& dir, ImportedDataset* out) {
  const std::string file = "li_ion_cells.csv";
  const CsvTable t = ReadCsv(dir + "/" + file);
  for (const auto& r : t.rows) {
    const Cells c{&t, &r};
    const std::string name = CleanName(c.Str("maker") + " " + c.Str("model"));
    const std::string ex = file + ":" + std::to_string(r.line) + " " + name;
    const auto cap = c.Pos("capacity_ah"), v = c.Pos("v_nom_v");
    if (!cap || !v) {
      out->report.Drop("batteries", "no capacity or voltage", ex);
      continue;
    }
    EntryBuilder b("pc_b_" + Slug(name), name + " (" + c.Str("format") + " cell)");
    b.Set("chemistry", "liion", "datasheet");
    b.Set("cells_series", 1, "derived");
    b.SetNum("capacity_ah", *cap, "datasheet");
    b.SetNum("voltage_nominal_v", *v, "datasheet");
    if (const auto i = c.Pos("i_cont_a")) b.SetNum("max_current_a", *i, "datasheet");
    if (const auto i = c.Pos("i_peak_a")) b.SetNum("peak_current_a", *i, "datasheet");
    if (const auto m = c.Pos("mass_kg")) b.SetNum("mass_kg", *m, "datasheet");
    b.Source(kPacksDataset, file + " line " + std::to_string(r.line) + " (iitmotorsports/batt-conf)",
             "the source project's cell figures (typical capacity); no internal resistance in the "
             "source: the battery model's lithium prior applies (battery/battery.h)");
    b.Tier("manufacturer_stated");
    out->batteries.push_back(b.Build());
    out->report.Keep("batteries");
  }
}

}  // namespace

ImportedDataset ImportPacksAndCells(const std::string& dir) {
  ImportedDataset out;
  out.report.dataset = "packs_and_cells";
  out.report.output_file = "packs_and_cells.json";
  out.comment =
      "Generated by dynosize ImportAll from shared/data/packs_and_cells: Tattu 12S/14S LiPo "
      "packs (symbench/uav-analysis commit 3249eff, GPL-3.0; maker values) and seven 18650/21700 "
      "Li-ion cells (iitmotorsports/batt-conf commit 0629264). FAST-UAV's 12S-16S rows are "
      "series/parallel stacks of the base units in fastuav.json and are not repeated. No pack "
      "or cell states a real internal resistance. Do not edit by hand.";
  ImportTattuPacks(dir, &out);
  ImportLiIonCells(dir, &out);
  return out;
}

}  // namespace dynosize
