// DriveCalc database (shared/data/drivecalc, exported from DCbase.dcd): motors, ESCs, battery
// cells and propellers. Units in the source: Rm [ohm], R and Ri [milliohm], Weight [g],
// Capacity [mAh], prop Dia/Pitch [in], thrust [g] = a*(n/1000)^b, power [W] = c*(n/1000)^d.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "catalog/esc_prior.h"
#include "catalog/motor_credibility.h"
#include "catalog/prop_credibility.h"
#include "common/atmosphere.h"
#include "common/units.h"
#include "importers/csv.h"
#include "importers/importers.h"

namespace dynosize {

namespace {

constexpr const char* kDataset = "DriveCalc DB";
// Speed at which io_a is evaluated from the loss terms: the no-load speed at 10 V DC, the
// voltage at which hobby datasheets most often state Io ("Io @ 10 V").
constexpr double kIoTestVoltageV = 10.0;

struct Row {
  const CsvTable* t;
  const CsvRow* r;
  std::string Str(const char* col) const { return t->Field(*r, t->Column(col)); }
  // A number; 0 for an empty cell (DriveCalc writes empty for "none").
  double Num(const char* col, bool* ok) const {
    const std::string f = Str(col);
    if (f.empty()) return 0.0;
    const auto v = ParseNumber(f);
    if (!v) {
      *ok = false;
      return 0.0;
    }
    return *v;
  }
  // "Motors.csv:12" for the report.
  std::string Where() const {
    const auto slash = t->path.find_last_of('/');
    return t->path.substr(slash == std::string::npos ? 0 : slash + 1) + ":" + std::to_string(r->line);
  }
};

std::string Ref(const char* file, const Row& row) {
  return std::string(file) + " myid " + row.Str("myid");
}

// Brushed motors by name: Graupner/Power "Speed 280..700", Mabuchi RS-xxx, "Bürsti" (German for
// brushed), Permax without "BL", GWS EPS gear drives. Everything else in DriveCalc is BLDC.
bool LooksBrushed(const std::string& name) {
  static const std::regex kBrushed(
      "(speed ?[0-9]{3})|(mabuchi)|(rs-[0-9]{3})|(b\xC3\xBCrst)|(permax [0-9])|(permax/)|"
      "(gws [0-9]{3} [0-9]+v)|(lightspeed [0-9]{3})",
      std::regex::icase);
  return std::regex_search(name, kBrushed);
}

// Letters and digits only, lowercase: "Welgard A28/14/06" and "Welgard A2814/06" agree.
std::string NameKey(const std::string& name) {
  std::string k;
  for (unsigned char c : name) {
    if (std::isalnum(c)) k.push_back(static_cast<char>(std::tolower(c)));
  }
  return k;
}

// Groups rows that are the same product under several ids: any of the keys of a row seen
// before puts it in that row's group. Returns, per row, the index of its group's first row.
std::vector<std::size_t> GroupDuplicates(const std::vector<std::vector<std::string>>& keys) {
  std::map<std::string, std::size_t> first;
  std::vector<std::size_t> group(keys.size());
  for (std::size_t i = 0; i < keys.size(); ++i) {
    group[i] = i;
    for (const auto& k : keys[i]) {
      if (k.empty()) continue;
      const auto it = first.find(k);
      if (it != first.end()) {
        group[i] = group[it->second];
        break;
      }
    }
    for (const auto& k : keys[i]) {
      if (!k.empty()) first.emplace(k, i);
    }
  }
  return group;
}

// "; same product as myid 1156 (merged)" for the kept row of a group, "" otherwise.
std::string MergedNote(const std::vector<std::size_t>& group, std::size_t i,
                       const std::vector<std::string>& myids, std::string* reference) {
  std::string others;
  for (std::size_t k = i + 1; k < group.size(); ++k) {
    if (group[k] == i) others += (others.empty() ? "" : ", ") + myids[k];
  }
  if (others.empty()) return "";
  *reference += " (merged: also myid " + others + ")";
  return "; the same product is listed as myid " + others + ": merged, values of myid " +
         myids[i] + " kept";
}

// The gear table (Gear.csv): myid -> (ratio, efficiency).
// Absent file: an empty table (every geared motor's efficiency assumed), said in the report.
std::map<std::string, std::pair<double, double>> ReadGearTable(const std::string& dir, ImportedDataset* out) {
  std::map<std::string, std::pair<double, double>> gears;
  if (!std::filesystem::exists(dir + "/Gear.csv")) {
    out->report.notes.push_back("Gear.csv absent: every geared motor's gear_efficiency assumed");
    return gears;
  }
  const CsvTable t = ReadCsv(dir + "/Gear.csv");
  for (const auto& r : t.rows) {
    const Row row{&t, &r};
    bool ok = true;
    const double ratio = row.Num("ratG", &ok), eta = row.Num("EtaG", &ok);
    if (ok && ratio >= 1.0 && eta > 0.0 && eta <= 1.0) gears[row.Str("myid")] = {ratio, eta};
  }
  return gears;
}

// A gearbox's efficiency when DriveCalc's gear table has none for the motor (no gear linked,
// or a linked gear of another ratio): the median of the table's 63 single-stage gears (0.95-
// 0.984, 0.9 for the cheapest; docs/model.md section 12).
constexpr double kDefaultGearEfficiency = 0.96;
// A linked gear-table row is the motor's gearbox when its ratio is the name's within this
// (LMT's "6:1" is Reisenauer's 5.94:1).
constexpr double kGearRatioMatchRel = 0.02;

// Geared motors whose name states no ratio (issue 51 item 3). DriveCalc stores a geared
// motor's kV at the output shaft (docs/model.md section 12); run as a direct drive at that Kv,
// such a motor has N x its real motor constant and wins heavy-lift searches (dc_m_1829 "Turnigy
// T600 Heli (880kv)", 164.8 rpm/V at 365 g, picked for a 50 kg octocopter). Evidence:
//  (1) the Kv the name states (KvFromMotorName) over DriveCalc's kV, q. On the direct-drive
//      motors whose name states a Kv, q is 0.63-1.21 (275 motors, 271 within 21 % of 1); q >=
//      kNameKvOutputMin says the stored kV is the output shaft's (no direct drive reaches it, and
//      it is below the smallest ratio in Gear.csv, 1.5).
//  (3) the gear DriveCalc links to the motor (mgear_id into Gear.csv, a ratio and efficiency).
//  (2) the motor constant against mass (catalog/motor_credibility.h): with the output shaft's
//      kV a geared unit's Km is 0.83-4.9x the mass law (median 1.70), with its motor's Kv
//      0.17-1.12x; Catalog::Load refuses a geared entry above kGearedKmRatioMax.
// The ratio is determined when (1) and (3) agree: q within kNameKvMatchRel of the linked gear's
// ratio (the scatter of q around 1 on direct drives: their largest q is 1.21). The entry is then geared with the
// linked gear: kv_rpm_per_v = ratio x DriveCalc's kV (the motor's Kv that keeps DriveCalc's
// measured propeller speeds; the name's Kv is nominal), gear_efficiency from Gear.csv.
// Excluded ("geared ... no ratio to run it with"): q >= kNameKvOutputMin without a linked gear
// of that ratio; or no Kv in the name, a linked gear above 1:1 and Km with DriveCalc's kV above
// kGearedKmRatioMax x the mass law (the stored kV reads as the output shaft's by the test
// Catalog::Load applies to geared entries, and nothing in the name says which ratio). A linked
// gear with a Km below that, or a name Kv that is DriveCalc's kV (q near 1: the name rules),
// stays direct drive, counted in the report.
constexpr double kNameKvOutputMin = 1.4;
constexpr double kNameKvMatchRel = 0.21;

struct UnnamedGear {
  enum Kind { kDirect, kGeared, kExcluded } kind = kDirect;
  double ratio = 1.0;
  double efficiency = 1.0;
  std::string note;     // appended to source.note (geared)
  std::string exclude;  // the reason (excluded)
  bool linked_left_direct = false;  // a linked gear above 1:1, left direct drive
  bool name_kv_below = false;       // the name's Kv well below DriveCalc's kV (q < 1 - kNameKvMatchRel)
  bool by_name_kv = false;          // excluded by the name's Kv (else by the linked gear and Km)
};

std::string Fmt(double x, int digits = 4) {
  std::ostringstream s;
  s.precision(digits);
  s << x;
  return s.str();
}

UnnamedGear JudgeUnnamedGear(const std::string& name, double kv_db, double rm_dc_ohm, double mass_kg,
                             const std::string& gear_id,
                             const std::map<std::string, std::pair<double, double>>& gear_table) {
  UnnamedGear u;
  const auto linked_it = gear_table.find(gear_id);
  const bool linked = linked_it != gear_table.end() && linked_it->second.first > 1.0;
  const double r = linked ? linked_it->second.first : 1.0;
  const std::string gear_text =
      linked ? "Gear.csv myid " + gear_id + " (" + Fmt(r) + ":1, efficiency " + Fmt(linked_it->second.second) + ")"
             : "";
  const NameKv nkv = KvFromMotorName(name);
  if (nkv.stated) {
    const double q = nkv.kv_rpm_per_v / kv_db;
    const std::string states = "the name states " + Fmt(nkv.kv_rpm_per_v, 6) + " kV (\"" + nkv.token +
                               "\"), the entry " + Fmt(kv_db) + " rpm/V (x" + Fmt(q, 3) + ")";
    if (q < 1.0 - kNameKvMatchRel) u.name_kv_below = true;
    if (q < kNameKvOutputMin) {
      u.linked_left_direct = linked;
      return u;
    }
    if (linked && std::fabs(q / r - 1.0) <= kNameKvMatchRel) {
      u.kind = UnnamedGear::kGeared;
      u.ratio = r;
      u.efficiency = linked_it->second.second;
      u.note = "; geared " + Fmt(r) + ":1 without a ratio in the name: " + states +
               ": the output shaft's Kv; DriveCalc links " + gear_text + ", x" + Fmt(q, 3) + " within " +
               Fmt(100 * kNameKvMatchRel, 2) + " % of it: gear_ratio and gear_efficiency from Gear.csv, " +
               "kv_rpm_per_v = " + Fmt(r) + " x DB kV (the motor's; the name's Kv is nominal), loss terms " +
               "moved to the motor shaft";
      return u;
    }
    u.kind = UnnamedGear::kExcluded;
    u.by_name_kv = true;
    u.exclude = "geared: " + states + ": the output shaft's Kv; no ratio to run it with (" +
                (linked ? "the linked " + gear_text + " is not x" + Fmt(q, 3) + " within " +
                              Fmt(100 * kNameKvMatchRel, 2) + " %"
                        : std::string("no gear linked in Gear.csv")) +
                ")";
    return u;
  }
  if (!linked) return u;
  const double km_ratio = GearedKmRatio(kv_db, rm_dc_ohm, mass_kg);
  if (km_ratio > kGearedKmRatioMax) {
    u.kind = UnnamedGear::kExcluded;
    u.exclude = "geared: DriveCalc links " + gear_text + " and the motor constant with the entry's " + Fmt(kv_db) +
                " rpm/V is " + Fmt(km_ratio, 3) + "x the typical one of its mass (above " + Fmt(kGearedKmRatioMax) +
                "x: the output shaft's Kv, catalog/motor_credibility.h); the name states neither a ratio nor a " +
                "Kv: no ratio to run it with";
    return u;
  }
  u.linked_left_direct = true;
  return u;
}

// Pass 1 of ImportMotors: the rows that are motors at all, their myids and duplicate keys.
struct MotorRows {
  std::vector<const CsvRow*> rows;
  std::vector<std::vector<std::string>> keys;
  std::vector<std::string> myids;
};

MotorRows UsableMotorRows(const CsvTable& t, ImportedDataset* out) {
  MotorRows m;
  auto& rows = m.rows;
  auto& keys = m.keys;
  auto& myids = m.myids;
  for (const auto& r : t.rows) {
    const Row row{&t, &r};
    const std::string name = CleanName(row.Str("Name"));
    const std::string example = row.Where() + " " + name;
    bool ok = true;
    const double kv = row.Num("kV", &ok), rm = row.Num("Rm", &ok);
    for (const char* col : {"Imax", "Weight", "K", "MvK", "kL"}) row.Num(col, &ok);
    if (!ok) {
      out->report.Drop("motors", "malformed number", example);
      continue;
    }
    if (name.empty()) {
      out->report.Drop("motors", "no name", example);
      continue;
    }
    if (!(kv > 0)) {
      out->report.Drop("motors", "kV = 0 placeholder", example);
      continue;
    }
    if (!(rm > 0)) {
      out->report.Drop("motors", "Rm = 0 placeholder", example);
      continue;
    }
    if (const NameGearRatio g = GearRatioFromMotorName(name); !g.error.empty()) {
      out->report.Drop("motors", "gear ratio in the name not usable: " + g.error, example);
      continue;
    }
    rows.push_back(&r);
    myids.push_back(row.Str("myid"));
    // The same numbers to every stated digit (kV, Rm, mass, losses) or the same name and kV.
    keys.push_back({"n|" + row.Str("kV") + "|" + row.Str("Rm") + "|" + row.Str("Weight") + "|" +
                        row.Str("MvK") + "|" + row.Str("kL"),
                    "k|" + NameKey(name) + "|" + row.Str("kV")});
  }
  return m;
}

// What ImportMotors counted of the gears, for the report's notes (GearNotes).
struct GearCounts {
  std::size_t geared = 0, geared_table_eta = 0, colon_not_ratio = 0, linked_not_named = 0;
  std::size_t geared_by_evidence = 0, excluded_name_kv = 0, excluded_km = 0, linked_left_direct = 0,
              name_kv_below = 0;
  std::vector<std::string> evidence_examples;
};

void GearNotes(const GearCounts& c, ImportedDataset* out);

void ImportMotors(const std::string& dir, ImportedDataset* out) {
  const CsvTable t = ReadCsv(dir + "/Motors.csv");
  const auto gear_table = ReadGearTable(dir, out);
  GearCounts c;
  auto& geared = c.geared;
  auto& geared_table_eta = c.geared_table_eta;
  auto& colon_not_ratio = c.colon_not_ratio;
  auto& linked_not_named = c.linked_not_named;
  auto& geared_by_evidence = c.geared_by_evidence;
  auto& excluded_name_kv = c.excluded_name_kv;
  auto& excluded_km = c.excluded_km;
  auto& linked_left_direct = c.linked_left_direct;
  auto& name_kv_below = c.name_kv_below;
  auto& evidence_examples = c.evidence_examples;
  if (t.was_latin1) out->report.notes.push_back("Motors.csv decoded as Latin-1");
  const MotorRows usable = UsableMotorRows(t, out);
  const auto& rows = usable.rows;
  const auto& myids = usable.myids;
  const std::vector<std::size_t> group = GroupDuplicates(usable.keys);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const Row row{&t, rows[i]};
    const std::string name = CleanName(row.Str("Name"));
    if (group[i] != i) {
      out->report.Drop("motors", "same product as another id: merged into it",
                       row.Where() + " " + name + " -> dc_m_" + myids[group[i]]);
      continue;
    }
    bool ok = true;
    const double kv_db = row.Num("kV", &ok), rm = row.Num("Rm", &ok), imax = row.Num("Imax", &ok),
                 weight_g = row.Num("Weight", &ok), k_db = row.Num("K", &ok),
                 mvk_db = row.Num("MvK", &ok), kl_db = row.Num("kL", &ok);
    const bool brushed = LooksBrushed(name);
    // A geared motor (ratio N in its name): DriveCalc's kV, loss torques and MData speeds are
    // the output shaft's (its no-load points give n/U = kV within 1 %, and where a name or
    // datasheet gives the motor's Kv it is N x kV: docs/model.md section 12). The catalog stores the
    // motor's own: Kv = N*kV, loss torques /N (MvK) and /N^2 (kL, per motor rad/s), K/N; Io
    // below is unchanged by it (the same current at the same speed).
    const NameGearRatio gear = GearRatioFromMotorName(name);
    // No ratio in the name: the evidence that the stored kV is an output shaft's (JudgeUnnamedGear).
    const UnnamedGear unnamed =
        gear.stated ? UnnamedGear{}
                    : JudgeUnnamedGear(name, kv_db, rm, GramsToKg(weight_g), row.Str("mgear_id"), gear_table);
    const bool by_evidence = unnamed.kind == UnnamedGear::kGeared;
    const bool geared_entry = gear.stated || by_evidence;
    const double n = by_evidence ? unnamed.ratio : gear.ratio;
    const double kv = n * kv_db, mvk = mvk_db / n, kl = kl_db / (n * n), k = k_db / n;
    // docs/model.md section 8 (BLDC) / DC machine: KE from Kv; section 5: KT = sqrt(27/10)*KE (BLDC).
    const double ke = brushed ? KeFromKvBrushed(kv) : KeFromKvBldc(kv);
    const double kt = brushed ? ke : kPacPerVllIrms * ke;
    // DriveCalc's loss torque MvK + kL*omega is carried by the no-load current: docs/model.md
    // section 9, Io(omega) = (MvK + kL*omega)/KT, evaluated at the 10 V no-load speed.
    const double omega_ref = RpmToRadPerSec(kv * kIoTestVoltageV);
    const double io = (mvk + kl * omega_ref) / kt;

    EntryBuilder b("dc_m_" + myids[i], name);
    b.Set("type", brushed ? "brushed" : "bldc", "derived");
    b.SetNum("kv_rpm_per_v", kv, geared_entry ? "derived" : "datasheet");
    // DriveCalc's Rm is the R of its DC model U = n/Kv + R*I (catalog/conventions.h); a brushed
    // motor's circuit is that DC circuit itself.
    if (brushed) b.SetNum("rm_ohm", rm, "datasheet");
    else SetResistanceFromDc(&b, rm, "datasheet");
    b.SetNum("io_a", io, "derived", 4);
    b.Set("io_test_voltage_v", kIoTestVoltageV, "derived");  // our evaluation point, see kIoTestVoltageV
    const char* at_motor = geared_entry ? "derived" : "datasheet";
    if (mvk > 0) b.SetNum("loss_torque_nm", mvk, at_motor);
    if (kl > 0) b.SetNum("loss_torque_per_omega_nm_s_per_rad", kl, at_motor);
    if (k > 0) b.SetNum("rm_per_omega_ohm_s_per_rad", k, at_motor);
    std::string gear_note;
    if (gear.stated) {
      ++geared;
      // The gear table's efficiency where the motor's linked gear is the named ratio.
      const auto linked = gear_table.find(row.Str("mgear_id"));
      const bool from_table = linked != gear_table.end() &&
                              std::fabs(linked->second.first - n) <= kGearRatioMatchRel * n;
      b.SetNum("gear_ratio", n, "derived");
      if (from_table) {
        ++geared_table_eta;
        b.SetNum("gear_efficiency", linked->second.second, "datasheet");
      } else {
        b.SetNum("gear_efficiency", kDefaultGearEfficiency, "assumed");
      }
      std::ostringstream g;
      g << "; geared " << n << ":1 (\"" << gear.token << "\" in the name): kv_rpm_per_v = " << n << " x DB kV "
        << kv_db << " (the motor's; DriveCalc's kV and MData speeds are the output shaft's), loss terms "
        << "moved to the motor shaft; gear_efficiency "
        << (from_table ? "from Gear.csv myid " + row.Str("mgear_id") : std::string("assumed (no gear of this ratio in Gear.csv for it)"));
      gear_note = g.str();
    } else {
      const auto linked = gear_table.find(row.Str("mgear_id"));
      if (linked != gear_table.end() && linked->second.first > 1.0) ++linked_not_named;
      if (name.find(':') != std::string::npos) ++colon_not_ratio;
      if (unnamed.linked_left_direct) ++linked_left_direct;
      if (unnamed.name_kv_below) ++name_kv_below;
      if (by_evidence) {
        ++geared_by_evidence;
        b.SetNum("gear_ratio", n, "datasheet");  // Gear.csv's ratG of the linked gear
        b.SetNum("gear_efficiency", unnamed.efficiency, "datasheet");
        gear_note = unnamed.note;
        evidence_examples.push_back("dc_m_" + myids[i] + " " + name + " (" + Fmt(n) + ":1)");
      } else if (unnamed.kind == UnnamedGear::kExcluded) {
        ++(unnamed.by_name_kv ? excluded_name_kv : excluded_km);
        evidence_examples.push_back("dc_m_" + myids[i] + " " + name + " (excluded)");
      }
    }
    if (imax > 0) b.SetNum("max_current_a", imax, "datasheet");
    if (weight_g > 0) b.SetNum("mass_kg", GramsToKg(weight_g), "datasheet");
    std::string note = brushed ? "rm_ohm: DB Rm" : "rm_ohm = 0.7492 x DB Rm (DC circuit)";
    note += ", DB Rm ~1.6x below a fit of DriveCalc's own measurements";
    note += SetRatingOrExclude(&b, imax > 0,
                               weight_g > 0 ? std::optional<double>(GramsToKg(weight_g)) : std::nullopt,
                               brushed);
    if (brushed) note += "; brushed (by name)";
    note += gear_note;
    std::string reference = Ref("Motors.csv", row);
    note += MergedNote(group, i, myids, &reference);
    b.Source(kDataset, reference, note);
    b.Tier("user_contributed");
    Json entry = b.Build();
    if (unnamed.kind == UnnamedGear::kExcluded) {
      // "exclude" before "source", as EntryBuilder writes it; a rating's reason is kept.
      Json source = entry["source"];
      entry.erase("source");
      entry["exclude"] =
          entry.contains("exclude") ? entry["exclude"].get<std::string>() + "; " + unnamed.exclude : unnamed.exclude;
      source["note"] = source.value("note", std::string()) + "; excluded by default: " + unnamed.exclude;
      entry["source"] = std::move(source);
    }
    out->motors.push_back(std::move(entry));
    out->report.Keep("motors");
  }
  GearNotes(c, out);
}

void GearNotes(const GearCounts& c, ImportedDataset* out) {
  const auto& [geared, geared_table_eta, colon_not_ratio, linked_not_named, geared_by_evidence, excluded_name_kv,
               excluded_km, linked_left_direct, name_kv_below, evidence_examples] = c;
  std::ostringstream g;
  g << "motors geared by name: " << geared << " (gear_efficiency from Gear.csv for " << geared_table_eta << ", assumed "
    << kDefaultGearEfficiency << " for " << geared - geared_table_eta << "); " << colon_not_ratio
    << " names with ':' state no ratio (direct drive); " << linked_not_named
    << " motors link a gear above 1:1 in Gear.csv without a ratio in the name";
  out->report.notes.push_back(g.str());
  std::ostringstream e;
  e << "geared motors without a ratio in the name (the name's Kv over DB kV, the linked gear, Km vs mass): "
    << geared_by_evidence << " geared with the linked gear (the name's Kv / DB kV within "
    << Fmt(100 * kNameKvMatchRel, 2) << " % of its ratio), " << excluded_name_kv + excluded_km
    << " excluded by default as geared without a ratio to run them with (" << excluded_name_kv
    << " by the name's Kv >= " << kNameKvOutputMin << " x DB kV, " << excluded_km
    << " by a linked gear and Km above " << kGearedKmRatioMax << "x the mass law); left direct drive: "
    << linked_left_direct << " linking a gear with nothing else saying geared, " << name_kv_below
    << " whose name's Kv is below " << 1.0 - kNameKvMatchRel << " x DB kV";
  if (!evidence_examples.empty()) {
    e << ":";
    for (const auto& x : evidence_examples) e << " " << x << ";";
  }
  std::string en = e.str();
  if (en.back() == ';') en.pop_back();
  out->report.notes.push_back(en);
}

void ImportEscs(const std::string& dir, ImportedDataset* out) {
  const CsvTable t = ReadCsv(dir + "/ESC.csv");
  const EscPrior& prior = DefaultEscPrior();
  std::vector<std::vector<std::string>> keys;
  std::vector<std::string> myids;
  for (const auto& r : t.rows) {
    const Row row{&t, &r};
    myids.push_back(row.Str("myid"));
    keys.push_back({NameKey(CleanName(row.Str("Name"))) + "|" + row.Str("Imax")});
  }
  const std::vector<std::size_t> group = GroupDuplicates(keys);
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    const auto& r = t.rows[i];
    const Row row{&t, &r};
    const std::string name = CleanName(row.Str("Name"));
    const std::string example = row.Where() + " " + name;
    bool ok = true;
    const double imax = row.Num("Imax", &ok), ipeak = row.Num("Ipeak", &ok),
                 r_mohm = row.Num("R", &ok), weight_g = row.Num("Weight", &ok),
                 lipo_min = row.Num("LiPomin", &ok), lipo_max = row.Num("LiPomax", &ok);
    if (!ok) {
      out->report.Drop("escs", "malformed number", example);
      continue;
    }
    if (!(imax > 0)) {
      out->report.Drop("escs", "Imax = 0 placeholder (no current rating)", example);
      continue;
    }
    if (group[i] != i) {
      out->report.Drop("escs", "same product as another id: merged into it",
                       example + " -> dc_e_" + myids[group[i]]);
      continue;
    }
    EntryBuilder b("dc_e_" + row.Str("myid"), name);
    std::string note;
    if (r_mohm > 0) {
      b.SetNum("resc_ohm", MilliohmToOhm(r_mohm), "datasheet");
      note = "";
    } else {
      b.SetNum("resc_ohm", PriorEscResistanceOhm(imax), "assumed", 3);
      note = "R = 0 placeholder: resc_ohm from the Imax prior; ";
    }
    b.SetNum("c1", prior.c1, "assumed");
    b.SetNum("c0", prior.c0, "assumed");
    b.SetNum("tr_sat", prior.tr_sat, "assumed");
    b.SetNum("sat_slope", prior.sat_slope, "assumed");
    b.SetNum("max_current_a", imax, "datasheet");
    if (ipeak >= imax) b.SetNum("ipeak_a", ipeak, "datasheet");
    if (weight_g > 0) b.SetNum("mass_kg", GramsToKg(weight_g), "datasheet");
    if (lipo_min >= 1 && lipo_max >= lipo_min) {
      b.Set("cells_min", static_cast<int>(lipo_min), "datasheet");
      b.Set("cells_max", static_cast<int>(lipo_max), "datasheet");
      // 4.2 V per fully charged LiPo cell.
      b.SetNum("vdc_max_v", 4.2 * lipo_max, "derived");
    }
    if (ipeak > 0 && ipeak < imax) note += "Ipeak < Imax in the source, left out; ";
    std::string reference = Ref("ESC.csv", row);
    note += "c1, c0, tr_sat, sat_slope: esc_prior.h";
    note += MergedNote(group, i, myids, &reference);
    b.Source(kDataset, reference, note);
    b.Tier("user_contributed");
    out->escs.push_back(b.Build());
    out->report.Keep("escs");
  }
}

// Chemistry from the nominal cell voltage and the name.
std::pair<std::string, std::string> Chemistry(double volt, const std::string& name) {
  std::string lower = name;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  auto has = [&](const char* s) { return lower.find(s) != std::string::npos; };
  if (volt < 1.5) {
    if (has("nicd") || has("nicad")) return {"nicd", "derived"};
    return {"nimh", "assumed"};  // 1.2 V: NiMH or NiCd, the data set does not say
  }
  if (volt < 3.35 || has("fepo") || has("a123") || has("a 123") || has("life")) {
    return {"lifepo4", "derived"};
  }
  if (has("konion") || has("li-ion") || has("liion") || has("18650") || has("26650")) {
    return {"liion", "derived"};
  }
  return {"lipo", "derived"};
}

void ImportBatteries(const std::string& dir, ImportedDataset* out) {
  const CsvTable t = ReadCsv(dir + "/Batteries.csv");
  for (const auto& r : t.rows) {
    const Row row{&t, &r};
    const std::string name = CleanName(row.Str("Name"));
    const std::string example = row.Where() + " " + name;
    bool ok = true;
    const double imax = row.Num("Imax", &ok), ipeak = row.Num("Ipeak", &ok),
                 cap_mah = row.Num("Capacity", &ok), weight_g = row.Num("Weight", &ok),
                 ri_mohm = row.Num("Ri", &ok), volt = row.Num("Volt", &ok);
    if (!ok) {
      out->report.Drop("batteries", "malformed number", example);
      continue;
    }
    if (!(cap_mah > 0) || !(volt > 0)) {
      out->report.Drop("batteries",
                       "not a cell: no capacity or voltage (DriveCalc's 'Constant voltage' source)",
                       example);
      continue;
    }
    const auto [chem, chem_method] = Chemistry(volt, name);
    EntryBuilder b("dc_b_" + row.Str("myid"), name);
    b.Set("chemistry", chem, chem_method);
    b.Set("cells_series", 1, "datasheet");
    b.SetNum("capacity_ah", MahToAh(cap_mah), "datasheet");
    b.SetNum("voltage_nominal_v", volt, "datasheet");
    if (ri_mohm > 0) b.SetNum("ri_ohm", MilliohmToOhm(ri_mohm), "datasheet");
    if (imax > 0) b.SetNum("max_current_a", imax, "datasheet");
    if (ipeak > 0) b.SetNum("peak_current_a", ipeak, "datasheet");
    if (weight_g > 0) b.SetNum("mass_kg", GramsToKg(weight_g), "datasheet");
    std::string note;
    if (chem_method == "assumed") note += "1.2 V: NiMH assumed (DB does not tell NiMH from NiCd); ";
    if (ri_mohm <= 0) note += "Ri = 0 placeholder, left out; ";
    if (!note.empty()) note.resize(note.size() - 2);
    b.Source(kDataset, Ref("Batteries.csv", row), note);
    b.Tier("user_contributed");
    out->batteries.push_back(b.Build());
    out->report.Keep("batteries");
  }
}

// Density of a DriveCalc measurement from its altitude [m] and temperature [C]; 0/0 means not
// stated, and sea-level ISA is assumed.
double LawDensity(double alt_m, double temp_c, bool* assumed) {
  *assumed = alt_m == 0.0 && temp_c == 0.0;
  return *assumed ? kIsaSeaLevelRhoKgM3 : AirDensityKgM3(alt_m, temp_c);
}

// Speed range of DriveCalc's own measurements (MData.csv, loaded points with rpm) per
// propeller id: the range over which a propeller's power laws were seen to hold.
std::map<std::string, std::pair<double, double>> MeasuredRpmRanges(const std::string& dir) {
  std::map<std::string, std::pair<double, double>> out;
  const CsvTable t = ReadCsv(dir + "/MData.csv");
  const std::size_t c_n = t.Column("n"), c_p = t.Column("prop_id"), c_nl = t.Column("IsNoLoad");
  for (const auto& r : t.rows) {
    const std::string prop = t.Field(r, c_p);
    const auto n = ParseNumber(t.Field(r, c_n));
    if (prop.empty() || prop == "0" || t.Field(r, c_nl) == "1" || !n || !(*n > 0)) continue;
    auto it = out.find(prop);
    if (it == out.end()) out.emplace(prop, std::make_pair(*n, *n));
    else it->second = {std::min(it->second.first, *n), std::max(it->second.second, *n)};
  }
  return out;
}

void ImportProps(const std::string& dir, ImportedDataset* out) {
  const CsvTable t = ReadCsv(dir + "/Props.csv");
  const auto measured = MeasuredRpmRanges(dir);
  std::vector<std::vector<std::string>> keys;
  std::vector<std::string> myids;
  for (const auto& r : t.rows) {
    const Row row{&t, &r};
    myids.push_back(row.Str("myid"));
    keys.push_back({NameKey(CleanName(row.Str("Name"))) + "|" + row.Str("Dia") + "|" + row.Str("Pitch")});
  }
  const std::vector<std::size_t> group = GroupDuplicates(keys);
  std::size_t folding_count = 0, measured_range = 0;
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    const Row row{&t, &t.rows[i]};
    bool ok = true;
    const double dia_in = row.Num("Dia", &ok), pitch_in = row.Num("Pitch", &ok),
                 a = row.Num("a", &ok), bexp = row.Num("b", &ok), c = row.Num("c", &ok),
                 d = row.Num("d", &ok), alt_t = row.Num("AltThr", &ok),
                 tmp_t = row.Num("TmpThr", &ok), alt_p = row.Num("AltPwr", &ok),
                 tmp_p = row.Num("TmpPwr", &ok), max_rpm = row.Num("MaxRPM", &ok),
                 folder = row.Num("Folder", &ok);
    const std::string name = CleanName(row.Str("Name")) + " " + row.Str("Dia") + "x" + row.Str("Pitch");
    const std::string example = row.Where() + " " + name;
    if (!ok) {
      out->report.Drop("props", "malformed number", example);
      continue;
    }
    if (!(dia_in > 0)) {
      out->report.Drop("props", "no diameter", example);
      continue;
    }
    if (!(a > 0) || !(bexp > 0)) {
      out->report.Drop("props", "no thrust law (a = 0, b = 0 placeholders; power law only)", example);
      continue;
    }
    if (!(c > 0) || !(d > 0)) {
      out->report.Drop("props", "no power law (c = 0 or d = 0)", example);
      continue;
    }
    if (group[i] != i) {
      out->report.Drop("props", "same product as another id: merged into it",
                       example + " -> dc_p_" + myids[group[i]]);
      continue;
    }
    // Both laws are brought to sea-level ISA density (T and P scale linearly with rho, from
    // T = CT*rho*n^2*D^4 and P = CP*rho*n^3*D^5).
    bool t_assumed = false, p_assumed = false;
    const double rho_t = LawDensity(alt_t, tmp_t, &t_assumed);
    const double rho_p = LawDensity(alt_p, tmp_p, &p_assumed);
    const double diameter_m = InchToMeter(dia_in);
    EntryBuilder b("dc_p_" + myids[i], name);
    b.SetNum("diameter_m", diameter_m, "datasheet");
    if (pitch_in > 0) b.SetNum("pitch_m", InchToMeter(pitch_in), "datasheet");
    b.SetNum("thrust_law_n", GramForceToNewton(a) * kIsaSeaLevelRhoKgM3 / rho_t, "derived");
    b.SetNum("thrust_law_exp", bexp, "datasheet");
    b.SetNum("power_law_w", c * kIsaSeaLevelRhoKgM3 / rho_p, "derived");
    b.SetNum("power_law_exp", d, "datasheet");
    b.Set("law_rho_kg_m3", kIsaSeaLevelRhoKgM3, "derived");
    if (max_rpm > 0) b.SetNum("max_rpm", max_rpm, "datasheet");
    // Valid range (catalog/prop_credibility.h): DriveCalc's own measurements with this
    // propeller, else the assumed tip-speed band capped by the stated MaxRPM.
    std::string range_note;
    if (const auto m = measured.find(myids[i]); m != measured.end()) {
      b.SetNum("rpm_min", m->second.first, "measured", 5);
      b.SetNum("rpm_max", m->second.second, "measured", 5);
      range_note = "rpm range: DriveCalc's measurements with this prop (MData)";
      ++measured_range;
    } else {
      const double lo = RadPerSecToRpm(kDefaultTipSpeedLoMS / (diameter_m / 2.0));
      double hi = RadPerSecToRpm(kDefaultTipSpeedHiMS / (diameter_m / 2.0));
      if (max_rpm > 0) hi = std::min(hi, max_rpm);
      b.SetNum("rpm_min", lo, "assumed", 4);
      b.SetNum("rpm_max", std::max(hi, lo), max_rpm > 0 && hi == max_rpm ? "datasheet" : "assumed", 4);
      range_note = "rpm range: no measurements, tip speed 40-230 m/s assumed (MaxRPM cap)";
    }
    const bool folding = folder > 0 || NameSaysFolding(name);
    if (folding) {
      b.Set("folding", true, folder > 0 ? "datasheet" : "derived");
      ++folding_count;
    }
    std::string note = "thrust: " + row.Str("srcThr") + " at " + row.Str("AltThr") + " m " +
                       row.Str("TmpThr") + " C; power: " + row.Str("srcPwr") + " at " +
                       row.Str("AltPwr") + " m " + row.Str("TmpPwr") + " C";
    if (t_assumed || p_assumed) note += " (0 m 0 C = not stated: sea level assumed)";
    note += "; " + range_note;
    if (folding) note += "; folding";
    std::string reference = Ref("Props.csv", row);
    note += MergedNote(group, i, myids, &reference);
    b.Source(kDataset, reference, note);
    b.Tier("user_contributed");
    KeepAuditedProp(b.Build(), example, out);
  }
  out->report.notes.push_back(
      "Props.csv: valid rpm range from DriveCalc's measurements (MData) for " +
      std::to_string(measured_range) + " props, assumed tip-speed band for the rest; " +
      std::to_string(folding_count) + " folding (Folder column or name)");
}

}  // namespace

NameGearRatio GearRatioFromMotorName(const std::string& name) {
  NameGearRatio g;
  // "<N>:<M>" anywhere a number may start; only M = 1 is a ratio the model takes.
  static const std::regex kColon("(^|[\\s/(\\-])([0-9]+(?:[.,][0-9]+)?)\\s*:\\s*([0-9]+(?:[.,][0-9]+)?)(?![0-9])");
  static const std::regex kSlash("\\s([0-9]+[.,][0-9]+)/1$");
  std::smatch m;
  std::string num, den = "1";
  if (std::regex_search(name, m, kColon)) {
    num = m[2].str();
    den = m[3].str();
    g.token = num + ":" + den;
  } else if (std::regex_search(name, m, kSlash)) {
    num = m[1].str();
    g.token = num + "/1";
  } else {
    return g;
  }
  std::replace(num.begin(), num.end(), ',', '.');
  std::replace(den.begin(), den.end(), ',', '.');
  const double n = std::stod(num), d = std::stod(den);
  if (d != 1.0) {
    g.error = "\"" + g.token + "\": a ratio must be written N:1";
  } else if (!(n >= 1.0 && n <= 100.0)) {
    g.error = "\"" + g.token + "\": the ratio must be 1-100 motor turns per propeller turn";
  } else if (n > 1.0) {  // "1:1" is direct drive
    g.stated = true;
    g.ratio = n;
  }
  return g;
}

namespace {

bool IsDigit(char c) { return c >= '0' && c <= '9'; }
bool IsAlpha(char c) { return std::isalpha(static_cast<unsigned char>(c)) != 0; }

// The whole number of 2-5 digits ending just before `end` (before == true) or starting at
// `begin`; "" when there is none or it is part of a decimal or of a longer token.
std::string NumberBefore(const std::string& s, std::size_t end) {
  std::size_t b = end;
  while (b > 0 && IsDigit(s[b - 1])) --b;
  if (end - b < 2 || end - b > 5) return "";
  if (b > 0 && (IsAlpha(s[b - 1]) || s[b - 1] == '.' || s[b - 1] == ',')) return "";
  return s.substr(b, end - b);
}
std::string NumberAfter(const std::string& s, std::size_t begin) {
  std::size_t e = begin;
  while (e < s.size() && IsDigit(s[e])) ++e;
  if (e - begin < 2 || e - begin > 5) return "";
  if (e < s.size() && (s[e] == '.' || s[e] == ',') && e + 1 < s.size() && IsDigit(s[e + 1])) return "";
  return s.substr(begin, e - begin);
}

}  // namespace

NameKv KvFromMotorName(const std::string& name) {
  NameKv out;
  std::string value;  // the one Kv of every "kv" token, "" = none yet
  bool conflict = false;
  for (std::size_t i = 0; i + 1 < name.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(name[i])) != 'k' ||
        std::tolower(static_cast<unsigned char>(name[i + 1])) != 'v') {
      continue;
    }
    if ((i > 0 && IsAlpha(name[i - 1])) || (i + 2 < name.size() && IsAlpha(name[i + 2]))) continue;
    // A number attached to the token, or one space away.
    std::string before = NumberBefore(name, i), after = NumberAfter(name, i + 2);
    const bool before_attached = !before.empty();
    const bool after_attached = !after.empty();
    if (before.empty() && i > 0 && name[i - 1] == ' ') before = NumberBefore(name, i - 1);
    if (after.empty() && i + 2 < name.size() && name[i + 2] == ' ') after = NumberAfter(name, i + 3);
    std::string kv, token;
    if (!before.empty() && (after.empty() || (before_attached && !after_attached))) {
      kv = before;
      token = before + (before_attached ? "" : " ") + name.substr(i, 2);
    } else if (!after.empty() && (before.empty() || (after_attached && !before_attached))) {
      kv = after;
      token = name.substr(i, 2) + (after_attached ? "" : " ") + after;
    } else {
      continue;  // none, or two numbers of the same standing
    }
    if (!value.empty() && std::stod(value) != std::stod(kv)) conflict = true;
    if (value.empty()) {
      value = kv;
      out.token = token;
    }
  }
  if (conflict) return NameKv{};
  if (value.empty()) {
    // Maker conventions (the header): the last token of the name is the Kv.
    static const std::regex kHimax("^himax\\s+[a-z]{0,2}[0-9]{4}-([0-9]{3,4})$", std::regex::icase);
    static const std::regex kMedusa("^medusa\\s+(?:mr-)?[0-9]{2,3}-[0-9]{2,3}-([0-9]{4})(?:\\s.*)?$",
                                    std::regex::icase);
    std::smatch m;
    if (std::regex_match(name, m, kHimax) || std::regex_match(name, m, kMedusa)) {
      value = m[1].str();
      out.token = "-" + value;  // the maker's naming
    }
  }
  if (value.empty()) return out;
  out.kv_rpm_per_v = std::stod(value);
  if (!(out.kv_rpm_per_v >= 10.0)) return NameKv{};
  out.stated = true;
  return out;
}

ImportedDataset ImportDriveCalc(const std::string& dir) {
  ImportedDataset out;
  out.report.dataset = "drivecalc";
  out.report.output_file = "drivecalc.json";
  out.comment =
      "Generated by dynosize ImportAll from shared/data/drivecalc: the DriveCalc database "
      "(drivecalc.de, Christian Persson; DCbase.dcd export from "
      "github.com/dariomangoni/DriveCalculatorMatlab commit 4451ac8; user-contributed entries, "
      "redistribution terms unclear). 'datasheet' = the value as stored in the DB. Units "
      "converted: g -> kg, mOhm -> ohm, mAh -> Ah, in -> m, gf -> N. Motors: ke/kt from kV "
      "(model.md sections 5, 8); rm_dc_ohm is DriveCalc's stored Rm, which a fit of DriveCalc's own "
      "measurement points (MData) finds ~1.6x too small (deciles 1.1-3.9x): a lower bound until "
      "refitted; io_a = (MvK + kL*omega)/kt at the no-load speed at 10 V DC (model.md section 9), "
      "in rms amperes; MvK, kL, K kept as loss_torque_nm, loss_torque_per_omega_nm_s_per_rad, "
      "rm_per_omega_ohm_s_per_rad. ESCs: c1, c0, tr_sat, sat_slope (and resc_ohm where R = 0) "
      "from the esc_prior.h prior, marked assumed. Batteries: one cell position each, per-cell "
      "values. Props: static power laws rescaled from the stated altitude/temperature to "
      "1.225 kg/m^3; no forward-flight data; valid rpm range rpm_min/rpm_max from DriveCalc's own "
      "measurements with the prop (MData) or an assumed tip-speed band; props whose figure of "
      "merit exceeds the envelope of measured props of their size class are derated "
      "(power_derate_factor), FM > 1 dropped. Motors: rm_ohm = 0.7492 x DB Rm (the DC circuit's "
      "R, kept as rm_dc_ohm; catalog/conventions.h); same product under several ids merged. "
      "Do not edit by hand: see catalog/README.md.";
  ImportMotors(dir, &out);
  ImportEscs(dir, &out);
  ImportBatteries(dir, &out);
  ImportProps(dir, &out);
  return out;
}

}  // namespace dynosize
