// `dynosize catalog list|show|validate|schema`.
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <utility>

#include "api/catalog_json.h"
#include "catalog/catalog.h"
#include "catalog/in_system.h"
#include "catalog/prop_credibility.h"
#include "catalog/prop_reynolds.h"
#include "catalog/schema.h"
#include "commands.h"
#include "common/error.h"
#include "common/json_pretty.h"
#include "common/text_format.h"
#include "common/units.h"

namespace dynosize::cli {

namespace {

api::CatalogListRequest ListRequest(const CatalogListOptions& o) {
  return {o.kind, o.kv_min, o.kv_max, o.mass_max_kg, o.current_min_a};
}

// A table cell: the value times `scale` with `prec` decimals, "-" when there is none.
std::string Cell(std::optional<double> v, double scale, int prec) { return v ? FixedText(*v * scale, prec) : "-"; }

std::string Clip(const std::string& s, std::size_t n) {
  return s.size() <= n ? s : s.substr(0, n - 1) + "~";
}

}  // namespace

int RunCatalogList(const CatalogListOptions& o) {
  api::CheckCatalogListRequest(ListRequest(o));
  const Catalog cat = Catalog::Load(o.catalog);
  const bool all = o.kind.empty();
  const auto motors = api::SelectForList(cat.motors(), ListRequest(o));
  const auto escs = api::SelectForList(cat.escs(), ListRequest(o));
  const auto props = api::SelectForList(cat.props(), ListRequest(o));
  const auto batteries = api::SelectForList(cat.batteries(), ListRequest(o));
  const bool motor_filter = o.kv_min || o.kv_max;
  if (o.json) {
    std::cout << DumpJson(api::CatalogListJson(cat, ListRequest(o)));
    return 0;
  }
  std::ostringstream out;
  if (all || o.kind == "motors") {
    out << "motors (" << motors.size() << ")\n";
    out << "  " << std::left << std::setw(28) << "id" << std::setw(40) << "name" << std::right
        << std::setw(6) << "type" << std::setw(8) << "Kv" << std::setw(10) << "KE mV*s"
        << std::setw(9) << "Rm mOhm" << std::setw(7) << "Io A" << std::setw(8) << "Imax A"
        << std::setw(8) << "mass g" << "  " << std::left << std::setw(20) << "tier" << "notes\n";
    for (const auto* m : motors) {
      std::string notes;
      for (const auto& k : m->assumed_keys) {
        if (k == "max_power_w") notes += "rating from mass ";
      }
      if (!m->exclude_reason.empty()) notes += "excluded: " + m->exclude_reason;
      out << "  " << std::left << std::setw(28) << Clip(m->id, 27) << std::setw(40) << Clip(m->name, 39)
          << std::right << std::setw(6) << (m->params.type == MotorType::kBldc ? "bldc" : "dc")
          << std::setw(8) << Cell(m->kv_rpm_per_v, 1, 0) << std::setw(10)
          << Cell(m->params.ke_v_s_per_rad, 1e3, 3) << std::setw(9) << Cell(m->params.rm_ohm, 1e3, 1)
          << std::setw(7) << Cell(m->params.io_a, 1, 2) << std::setw(8)
          << Cell(std::isfinite(m->params.max_current_a) ? std::optional<double>(m->params.max_current_a) : std::nullopt, 1, 1)
          << std::setw(8) << Cell(m->mass_kg, 1e3, 0) << "  " << std::left << std::setw(20)
          << TierName(m->tier) << notes << "\n";
    }
  }
  if ((all && !motor_filter) || o.kind == "escs") {
    out << "escs (" << escs.size() << ")\n";
    out << "  " << std::left << std::setw(28) << "id" << std::setw(40) << "name" << std::right
        << std::setw(10) << "RESC mOhm" << std::setw(7) << "C1" << std::setw(7) << "C0"
        << std::setw(8) << "TR_sat" << std::setw(7) << "slope" << std::setw(8) << "Imax A"
        << std::setw(8) << "mass g" << "\n";
    for (const auto* e : escs) {
      const auto& p = e->params;
      out << "  " << std::left << std::setw(28) << Clip(e->id, 27) << std::setw(40) << Clip(e->name, 39)
          << std::right << std::setw(10) << Cell(p.resc_ohm, 1e3, 1) << std::setw(7) << Cell(p.c1, 1, 3)
          << std::setw(7) << Cell(p.c0, 1, 3) << std::setw(8) << Cell(p.tr_sat, 1, 2) << std::setw(7)
          << Cell(p.sat_slope, 1, 2) << std::setw(8)
          << Cell(std::isfinite(p.max_current_a) ? std::optional<double>(p.max_current_a) : std::nullopt, 1, 0)
          << std::setw(8) << Cell(e->mass_kg, 1e3, 0)
          << (e->assumed_keys.empty() ? "" : "  (assumed: " + std::to_string(e->assumed_keys.size()) + " values)")
          << "\n";
    }
  }
  if ((all && !motor_filter) || o.kind == "props") {
    out << "props (" << props.size() << ")\n";
    out << "  " << std::left << std::setw(28) << "id" << std::setw(40) << "name" << std::right
        << std::setw(10) << "diam in" << std::setw(10) << "pitch in" << std::setw(8) << "mass g"
        << std::setw(8) << "FM max" << "  " << std::left << std::setw(22) << "tier" << "notes\n";
    for (const auto* p : props) {
      std::string notes;
      if (p->folding) notes += "folding ";
      if (p->power_derate_factor > 1.0) notes += "derated x" + Cell(p->power_derate_factor, 1, 3) + " ";
      out << "  " << std::left << std::setw(28) << Clip(p->id, 27) << std::setw(40) << Clip(p->name, 39)
          << std::right << std::setw(10) << Cell(p->diameter_m, 1 / 0.0254, 1) << std::setw(10)
          << Cell(p->pitch_m, 1 / 0.0254, 1) << std::setw(8) << Cell(p->mass_kg, 1e3, 0)
          << std::setw(8) << Cell(ScanFigureOfMerit(*p).fm_max, 1, 3) << "  " << std::left
          << std::setw(22) << TierName(p->tier) << notes << "\n";
    }
  }
  if ((all && !motor_filter) || o.kind == "batteries") {
    out << "batteries (" << batteries.size() << ")\n";
    out << "  " << std::left << std::setw(28) << "id" << std::setw(40) << "name" << std::right
        << std::setw(8) << "mass g" << "\n";
    for (const auto* b : batteries) {
      out << "  " << std::left << std::setw(28) << Clip(b->id, 27) << std::setw(40) << Clip(b->name, 39)
          << std::right << std::setw(8) << Cell(b->mass_kg, 1e3, 0) << "\n";
    }
  }
  std::cout << out.str();
  return 0;
}

int RunCatalogShow(const CatalogFolders& catalog, const std::string& id) {
  const Catalog cat = Catalog::Load(catalog);
  const Json out = api::CatalogShowJson(cat, id);
  std::cout << DumpJsonReadable(out);
  return 0;
}

int RunCatalogValidate(const CatalogFolders& catalog, bool json) {
  const auto problems = Catalog::Validate(catalog);
  std::string dir = catalog.base;
  for (const auto& added : catalog.added) dir += " + " + added;
  if (json) {
    Json j;
    j["valid"] = problems.empty();
    j["problems"] = problems;
    std::cout << DumpJson(j);
  } else if (problems.empty()) {
    const Catalog cat = Catalog::Load(catalog);
    std::cout << dir << ": valid: " << cat.motors().size() << " motors, " << cat.escs().size()
              << " ESCs, " << cat.props().size() << " props, " << cat.batteries().size()
              << " batteries, " << cat.prop_families().size() << " propeller families the search sizes\n";
    // What the physics rules and the importers' audit left, in numbers.
    std::vector<std::size_t> tiers(TierNames().size(), 0);
    std::size_t excluded = 0, derated = 0, folding = 0, estimated = 0;
    auto count = [&](const EntryBase& e) {
      ++tiers[static_cast<int>(e.tier)];
      excluded += !e.exclude_reason.empty();
    };
    for (const auto& m : cat.motors()) {
      count(m);
      for (const auto& k : m.assumed_keys) estimated += k == "max_power_w";
    }
    for (const auto& e : cat.escs()) count(e);
    for (const auto& b : cat.batteries()) count(b);
    for (const auto& p : cat.props()) {
      count(p);
      derated += p.power_derate_factor > 1.0;
      folding += p.folding;
    }
    std::cout << "  tiers: ";
    for (int t = 0; t < static_cast<int>(tiers.size()); ++t) {
      std::cout << (t ? ", " : "") << tiers[t] << " " << TierName(static_cast<DataTier>(t));
    }
    std::cout << "\n  no entry creates energy or beats momentum theory (model.md section 10); "
              << derated << " props derated to the FM envelope of measured props, " << folding
              << " folding; " << estimated << " motor ratings estimated from mass; " << excluded
              << " entries excluded by default\n";
  } else {
    for (const auto& p : problems) std::cout << p << "\n";
    std::cerr << dir << ": " << problems.size() << " problem" << (problems.size() == 1 ? "" : "s") << "\n";
  }
  return problems.empty() ? 0 : static_cast<int>(ExitCode::kDataError);
}

int RunCatalogSchema(bool json) {
  const ComponentKind kinds[] = {ComponentKind::kMotor, ComponentKind::kEsc, ComponentKind::kProp,
                                 ComponentKind::kBattery};
  Json j;
  std::ostringstream out;
  for (ComponentKind k : kinds) {
    Json arr = Json::array();
    out << KindArrayName(k) << ":\n";
    for (const auto& s : SchemaFor(k)) {
      arr.push_back({{"key", s.key}, {"required", s.required}, {"rule", DescribeRule(s)}, {"doc", s.doc}});
      out << "  " << std::left << std::setw(18) << s.key << (s.required ? " required " : " optional ")
          << DescribeRule(s) << ": " << s.doc << "\n";
    }
    j[KindArrayName(k)] = arr;
  }
  if (json) std::cout << DumpJson(j); else std::cout << out.str();
  return 0;
}

int RunCatalogPropReynolds(const CatalogFolders& catalog) {
  const Catalog cat = Catalog::Load(catalog);
  std::vector<const PropEntry*> measured;
  for (const PropEntry& p : cat.props()) {
    if (!UiucFamily(p.id).empty() && !p.static_table.rpm.empty()) measured.push_back(&p);
  }
  if (measured.empty()) throw DataError(catalog.base + ": no UIUC propeller with a static table (uiuc_propdb.json)");
  std::cout << ReynoldsReportMarkdown(measured);
  return 0;
}

}  // namespace dynosize::cli
