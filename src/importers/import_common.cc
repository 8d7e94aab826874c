#include "importers/import_common.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "catalog/catalog.h"
#include "catalog/conventions.h"
#include "catalog/prop_credibility.h"
#include "common/error.h"

namespace dynosize {

namespace {
constexpr std::size_t kMaxExamples = 3;
}

void DatasetReport::Drop(const std::string& kind, const std::string& reason,
                         const std::string& example) {
  for (auto& d : dropped) {
    if (d.kind == kind && d.reason == reason) {
      ++d.count;
      if (d.examples.size() < kMaxExamples) d.examples.push_back(example);
      return;
    }
  }
  dropped.push_back(DropCount{kind, reason, 1, {example}});
}

std::size_t DatasetReport::DroppedCount(const std::string& kind) const {
  std::size_t n = 0;
  for (const auto& d : dropped) {
    if (d.kind == kind) n += d.count;
  }
  return n;
}

std::map<std::string, std::size_t> ImportReport::TotalKept() const {
  std::map<std::string, std::size_t> total;
  for (const auto& d : datasets) {
    for (const auto& [kind, n] : d.kept) total[kind] += n;
  }
  return total;
}

std::string ImportReport::BriefReport() const {
  std::ostringstream out;
  bool first = true;
  for (const auto& [kind, n] : TotalKept()) {
    out << (first ? "" : ", ") << n << " " << kind;
    first = false;
  }
  std::size_t dropped = 0;
  for (const auto& d : datasets) {
    for (const auto& x : d.dropped) dropped += x.count;
  }
  out << " written to " << datasets.size() << " files; " << dropped << " rows dropped";
  return out.str();
}

std::string ImportReport::FullReport() const {
  std::ostringstream out;
  for (const auto& d : datasets) {
    out << d.dataset << " -> " << d.output_file << "\n";
    for (const auto& [kind, n] : d.kept) out << "  kept    " << n << " " << kind << "\n";
    for (const auto& x : d.dropped) {
      out << "  dropped " << x.count << " " << x.kind << ": " << x.reason;
      if (!x.examples.empty()) {
        out << " (e.g. ";
        for (std::size_t i = 0; i < x.examples.size(); ++i) out << (i ? "; " : "") << x.examples[i];
        out << ")";
      }
      out << "\n";
    }
    if (d.props_derated > 0) {
      out << "  derated " << d.props_derated << " props above the FM envelope (e.g. ";
      for (std::size_t i = 0; i < d.derated_examples.size(); ++i) out << (i ? "; " : "") << d.derated_examples[i];
      out << ")\n";
    }
    for (const auto& n : d.notes) out << "  note    " << n << "\n";
  }
  out << BriefReport() << "\n";
  return out.str();
}

Json ImportReport::ToJson() const {
  Json j = Json::array();
  for (const auto& d : datasets) {
    Json dj;
    dj["dataset"] = d.dataset;
    dj["output_file"] = d.output_file;
    dj["kept"] = Json::object();
    for (const auto& [kind, n] : d.kept) dj["kept"][kind] = n;
    dj["dropped"] = Json::array();
    for (const auto& x : d.dropped) {
      dj["dropped"].push_back(
          {{"kind", x.kind}, {"reason", x.reason}, {"count", x.count}, {"examples", x.examples}});
    }
    dj["props_derated"] = d.props_derated;
    dj["notes"] = d.notes;
    j.push_back(dj);
  }
  return Json{{"datasets", j}};
}

double RoundSig(double x, int digits) {
  if (x == 0.0 || !std::isfinite(x)) return x;
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, x);
  double v = 0.0;
  std::from_chars(buf, buf + std::char_traits<char>::length(buf), v);
  return v;
}

std::string Slug(const std::string& text) {
  std::string out;
  bool pending_sep = false;
  auto put = [&](const char* s) {
    if (pending_sep && !out.empty()) out.push_back('_');
    pending_sep = false;
    out += s;
  };
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (std::isalnum(c) && c < 0x80) {
      const char s[2] = {static_cast<char>(std::tolower(c)), 0};
      put(s);
    } else if (c == 0xC3 && i + 1 < text.size()) {
      const auto d = static_cast<unsigned char>(text[i + 1]);
      ++i;
      switch (d) {
        case 0xA4: case 0x84: put("ae"); break;
        case 0xB6: case 0x96: put("oe"); break;
        case 0xBC: case 0x9C: put("ue"); break;
        case 0x9F: put("ss"); break;
        default: pending_sep = true; break;
      }
    } else if (c == '.' && i > 0 && i + 1 < text.size() &&
               std::isdigit(static_cast<unsigned char>(text[i - 1])) &&
               std::isdigit(static_cast<unsigned char>(text[i + 1]))) {
      put(".");  // keep decimal points in sizes such as 9.5x5
    } else {
      pending_sep = true;
    }
  }
  return out;
}

std::string CleanName(const std::string& text) {
  std::string out;
  bool space = false;
  for (char c : text) {
    if (c == ' ' || c == '\t' || c == '\r' || c == '\n') {
      space = true;
    } else {
      if (space && !out.empty()) out.push_back(' ');
      space = false;
      out.push_back(c);
    }
  }
  return out;
}

EntryBuilder::EntryBuilder(const std::string& id, const std::string& name) {
  entry_ = Json::object();
  entry_["id"] = id;
  entry_["name"] = name;
}

EntryBuilder& EntryBuilder::Set(const std::string& key, const Json& value,
                                const std::string& method) {
  if (value.is_number_float() && !std::isfinite(value.get<double>())) {
    throw InternalError("importer produced a non-finite value for '" + key + "' in " +
                        entry_["id"].get<std::string>());
  }
  entry_[key] = value;
  if (!method.empty()) values_[key] = method;
  return *this;
}

EntryBuilder& EntryBuilder::SetNum(const std::string& key, double value, const std::string& method,
                                   int digits) {
  return Set(key, RoundSig(value, digits), method);
}

EntryBuilder& EntryBuilder::Source(const std::string& dataset, const std::string& reference,
                                   const std::string& note) {
  dataset_ = dataset;
  reference_ = reference;
  note_ = note;
  return *this;
}

EntryBuilder& EntryBuilder::Tier(const std::string& tier) {
  tier_ = tier;
  return *this;
}

Json EntryBuilder::Build() const {
  Json e = entry_;
  Json src = Json::object();
  src["dataset"] = dataset_;
  if (!reference_.empty()) src["reference"] = reference_;
  if (!values_.empty()) src["values"] = values_;
  if (!note_.empty()) src["note"] = note_;
  if (!tier_.empty()) src["tier"] = tier_;
  e["source"] = src;
  return e;
}

void SetResistanceFromDc(EntryBuilder* b, double r_dc_ohm, const std::string& method, int digits) {
  b->SetNum("rm_ohm", RmsCircuitResistanceFromDc(r_dc_ohm), "derived", digits);
  b->SetNum("rm_dc_ohm", r_dc_ohm, method, digits);
}

std::string SetRatingOrExclude(EntryBuilder* b, bool has_rating, std::optional<double> mass_kg,
                               bool brushed) {
  if (has_rating) return "";
  if (mass_kg && !brushed) {
    b->SetNum("max_power_w", EstimatedMotorPowerW(*mass_kg), "assumed", 3);
    return "; no rating in the source: max_power_w estimated from the mass (outrunner law "
           "10.81*m[g]^0.878 W, catalog/conventions.h)";
  }
  b->Set("exclude", brushed ? "no current or power rating (brushed: the outrunner mass law does "
                              "not apply)"
                            : "no current or power rating and no mass to estimate one from",
         "");
  return "; excluded by default: no rating";
}

PropAudit AuditProp(Json* entry) {
  PropAudit a;
  const PropEntry p = PropEntryFromJson(*entry);
  const PropFmScan scan = ScanFigureOfMerit(p);
  a.fm_max = scan.fm_max;
  a.envelope_max = FmEnvelopeFor(p.diameter_m).max;
  const std::string violation = PropMomentumViolation(p);
  if (!violation.empty()) {
    a.refused = true;
    a.why = violation;
    return a;
  }
  if (!(scan.fm_max > a.envelope_max)) return a;
  // Rounded up at 5 decimals, so that the derated entry sits at or below the envelope.
  a.factor = std::ceil(scan.fm_max / a.envelope_max * 1e5) / 1e5;
  if (!(a.factor > 1.0)) {  // above by less than the digits kept: leave the data as stated
    a.factor = 1.0;
    return a;
  }
  a.derated = true;
  Json& e = *entry;
  // 7 digits: the 6-digit rounding of a scaled number could undo the last 5e-6 of the factor.
  auto scale = [&](Json& v) { v = RoundSig(v.get<double>() * a.factor, 7); };
  if (e.contains("power_law_w")) scale(e["power_law_w"]);
  if (e.contains("cp_static")) scale(e["cp_static"]);
  if (e.contains("static_table")) {
    for (Json& v : e["static_table"]["cp"]) scale(v);
  }
  if (e.contains("j_tables")) {
    for (Json& t : e["j_tables"]) {
      for (Json& v : t["cp"]) scale(v);
    }
  }
  e["power_derate_factor"] = a.factor;
  // Keep "source" last (EntryBuilder's layout) and record the method.
  Json src = e["source"];
  e.erase("source");
  src["values"]["power_derate_factor"] = "derived";
  char buf[200];
  std::snprintf(buf, sizeof buf,
                "power data x%.4g: static FM up to %.3f in its valid range, above the %.3f of the "
                "best measured propeller of its class (prop_credibility.h)",
                a.factor, scan.fm_max, a.envelope_max);
  const std::string note = src.value("note", std::string());
  src["note"] = note.empty() ? std::string(buf) : note + "; " + buf;
  e["source"] = src;
  return a;
}

std::string FormatCatalogDocument(const std::string& comment, const Json& motors,
                                  const Json& escs, const Json& props, const Json& batteries) {
  std::string out = "{\n  \"comment\": " + Json(comment).dump();
  const std::pair<const char*, const Json*> kinds[] = {
      {"motors", &motors}, {"escs", &escs}, {"props", &props}, {"batteries", &batteries}};
  for (const auto& [name, arr] : kinds) {
    if (!arr->is_array() || arr->empty()) continue;
    out += ",\n  \"" + std::string(name) + "\": [\n";
    for (std::size_t i = 0; i < arr->size(); ++i) {
      std::string line = DumpJson((*arr)[i], -1);
      line.pop_back();  // DumpJson's final newline
      out += "    " + line + (i + 1 < arr->size() ? ",\n" : "\n");
    }
    out += "  ]";
  }
  out += "\n}\n";
  return out;
}

std::optional<double> DurationTextS(const std::string& text) {
  for (std::size_t i = 0; i < text.size();) {
    if (!std::isdigit(static_cast<unsigned char>(text[i]))) {
      ++i;
      continue;
    }
    std::size_t e = i;
    while (e < text.size() && (std::isdigit(static_cast<unsigned char>(text[e])) || text[e] == '.')) ++e;
    const std::string number = text.substr(i, e - i);
    std::size_t u = e;
    while (u < text.size() && text[u] == ' ') ++u;
    const bool unit_end = u + 1 >= text.size() || !std::isalpha(static_cast<unsigned char>(text[u + 1]));
    const double v = std::strtod(number.c_str(), nullptr);
    if (text.compare(u, 3, "min") == 0) return v * 60.0;
    if (u < text.size() && text[u] == 's' && unit_end) return v;
    i = e;
  }
  return std::nullopt;
}

}  // namespace dynosize
