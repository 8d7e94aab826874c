#include "catalog/catalog.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>

#include "catalog/schema.h"
#include "common/error.h"
#include "common/units.h"

namespace dynosize {

namespace {

constexpr std::size_t kMaxProblemsInError = 20;

std::string ValueText(const Json& v) {
  std::string s = v.dump();
  if (s.size() > 60) s = s.substr(0, 57) + "...";
  return s;
}

bool ValidId(const std::string& id) {
  if (id.empty() || id.size() > 120) return false;
  return std::all_of(id.begin(), id.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.' ||
           c == '+';
  });
}

bool TypeMatches(const KeySpec& spec, const Json& v) {
  switch (spec.type) {
    case ValueType::kNumber: return v.is_number();
    case ValueType::kInteger:
      return v.is_number_integer() ||
             (v.is_number_float() && std::floor(v.get<double>()) == v.get<double>());
    case ValueType::kString: return v.is_string();
    case ValueType::kBool: return v.is_boolean();
    case ValueType::kObject: return v.is_object();
    case ValueType::kArray: return v.is_array();
  }
  return false;
}

// Checks one value against its spec; returns the violated rule or "".
std::string CheckValue(const KeySpec& spec, const Json& v) {
  if (!TypeMatches(spec, v)) return "must be " + DescribeRule(spec);
  if (spec.type == ValueType::kNumber || spec.type == ValueType::kInteger) {
    const double x = v.get<double>();
    const bool below = spec.min_exclusive ? !(x > spec.min) : !(x >= spec.min);
    const bool above = spec.max_exclusive ? !(x < spec.max) : !(x <= spec.max);
    if (!std::isfinite(x) || below || above) return "must be " + DescribeRule(spec);
  }
  if (spec.type == ValueType::kString && !spec.choices.empty() &&
      std::find(spec.choices.begin(), spec.choices.end(), v.get<std::string>()) ==
          spec.choices.end()) {
    return "must be " + DescribeRule(spec);
  }
  return "";
}

std::size_t EditDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t sub = prev[j - 1] + (std::tolower(a[i - 1]) == std::tolower(b[j - 1]) ? 0 : 1);
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, sub});
    }
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

double Get(const Json& e, const char* key, double fallback) {
  const auto it = e.find(key);
  return it == e.end() ? fallback : it->get<double>();
}

std::optional<double> GetOpt(const Json& e, const char* key) {
  const auto it = e.find(key);
  if (it == e.end()) return std::nullopt;
  return it->get<double>();
}

}  // namespace

const char* KindArrayName(ComponentKind kind) {
  switch (kind) {
    case ComponentKind::kMotor: return "motors";
    case ComponentKind::kEsc: return "escs";
    case ComponentKind::kProp: return "props";
    case ComponentKind::kBattery: return "batteries";
  }
  return "?";
}

const char* KindNoun(ComponentKind kind) {
  switch (kind) {
    case ComponentKind::kMotor: return "motor";
    case ComponentKind::kEsc: return "ESC";
    case ComponentKind::kProp: return "propeller";
    case ComponentKind::kBattery: return "battery";
  }
  return "?";
}

void Catalog::AddDocument(const Json& doc, const std::string& file,
                          std::vector<std::string>* problems) {
  if (!doc.is_object()) {
    problems->push_back(file + ": the top level must be an object with arrays \"motors\", "
                               "\"escs\", \"props\" and/or \"batteries\"");
    return;
  }
  static const ComponentKind kKinds[] = {ComponentKind::kMotor, ComponentKind::kEsc,
                                         ComponentKind::kProp, ComponentKind::kBattery};
  for (auto it = doc.begin(); it != doc.end(); ++it) {
    const bool known = std::any_of(std::begin(kKinds), std::end(kKinds), [&](ComponentKind k) {
      return it.key() == KindArrayName(k);
    });
    if (!known && it.key() != "comment") {
      problems->push_back(file + ": unknown top-level key \"" + it.key() +
                          "\": allowed are motors, escs, props, batteries, comment");
    }
  }
  for (ComponentKind kind : kKinds) {
    const auto arr = doc.find(KindArrayName(kind));
    if (arr == doc.end()) continue;
    if (!arr->is_array()) {
      problems->push_back(file + ": \"" + KindArrayName(kind) + "\" must be an array");
      continue;
    }
    const auto& schema = SchemaFor(kind);
    for (std::size_t i = 0; i < arr->size(); ++i) {
      const Json& e = (*arr)[i];
      std::string where = file + ": " + KindArrayName(kind) + "[" + std::to_string(i) + "]";
      if (!e.is_object()) {
        problems->push_back(where + ": must be an object, found " + ValueText(e));
        continue;
      }
      const auto id_it = e.find("id");
      std::string id;
      if (id_it != e.end() && id_it->is_string()) {
        id = id_it->get<std::string>();
        where += " id=" + id;
      }
      const std::size_t before = problems->size();
      // One problem line: file, entry, key, value (when present) and the rule.
      auto bad = [&](const std::string& key, const std::string& rule, const Json* value = nullptr) {
        if (!value && e.contains(key)) value = &e[key];
        problems->push_back(where + ": key '" + key + "'" +
                            (value ? " = " + ValueText(*value) : std::string()) + ": " + rule);
      };
      // Unknown keys, listed sorted.
      std::set<std::string> unknown;
      for (auto k = e.begin(); k != e.end(); ++k) {
        const bool in_schema = std::any_of(schema.begin(), schema.end(),
                                           [&](const KeySpec& s) { return s.key == k.key(); });
        if (!in_schema) unknown.insert(k.key());
      }
      for (const auto& k : unknown) bad(k, std::string("unknown key for a ") + KindNoun(kind));
      for (const KeySpec& spec : schema) {
        const auto v = e.find(spec.key);
        if (v == e.end()) {
          if (spec.required) bad(spec.key, "missing (required: " + spec.doc + ")");
          continue;
        }
        const std::string rule = CheckValue(spec, *v);
        if (!rule.empty()) bad(spec.key, rule);
      }
      if (id_it != e.end() && id_it->is_string() && !ValidId(id)) {
        bad("id", "must be 1-120 characters of letters, digits, _ - . +");
      }
      // source: {dataset (required), reference, values: {key: method}, note}.
      const auto src = e.find("source");
      if (src != e.end() && src->is_object()) {
        for (auto k = src->begin(); k != src->end(); ++k) {
          const std::string& sk = k.key();
          if (sk == "dataset" || sk == "reference" || sk == "note") {
            if (!k->is_string()) bad("source." + sk, "must be a string", &*k);
          } else if (sk == "values") {
            if (!k->is_object()) {
              bad("source.values", "must be an object {key: method}");
              continue;
            }
            for (auto m = k->begin(); m != k->end(); ++m) {
              const auto& methods = ProvenanceMethods();
              if (!e.contains(m.key())) {
                bad("source.values." + m.key(), "names a key the entry does not have");
              } else if (!m->is_string() ||
                         std::find(methods.begin(), methods.end(), m->get<std::string>()) ==
                             methods.end()) {
                bad("source.values." + m.key(),
                    "must be one of datasheet, measured, fitted, derived, assumed", &*m);
              }
            }
          } else {
            bad("source." + sk, "unknown key: allowed are dataset, reference, values, note", &*k);
          }
        }
        if (!src->contains("dataset")) bad("source.dataset", "missing (required)");
      }
      if (kind == ComponentKind::kMotor && !e.contains("ke_v_s_per_rad") &&
          !e.contains("kv_rpm_per_v")) {
        bad("ke_v_s_per_rad", "missing: a motor needs ke_v_s_per_rad or kv_rpm_per_v");
      }
      if (!id.empty()) {
        const auto prev = id_file_.find(id);
        if (prev != id_file_.end()) {
          bad("id", "duplicate id: already used in " + prev->second);
        }
      }
      if (problems->size() != before) continue;

      // The entry is valid: convert it once, here, to SI parameters.
      id_file_[id] = where;
      EntryBase base;
      base.id = id;
      base.name = e["name"].get<std::string>();
      base.file = file;
      base.json = e;
      if (const auto vals = src->find("values"); vals != src->end()) {
        for (auto m = vals->begin(); m != vals->end(); ++m) {
          if (m->get<std::string>() == "assumed") base.assumed_keys.push_back(m.key());
        }
      }
      switch (kind) {
        case ComponentKind::kMotor: {
          MotorEntry m;
          static_cast<EntryBase&>(m) = std::move(base);
          MotorParams& p = m.params;
          p.type = e["type"].get<std::string>() == "brushed" ? MotorType::kBrushed : MotorType::kBldc;
          m.kv_rpm_per_v = GetOpt(e, "kv_rpm_per_v");
          const double ke_from_kv =
              m.kv_rpm_per_v ? (p.type == MotorType::kBldc ? KeFromKvBldc(*m.kv_rpm_per_v)
                                                           : KeFromKvBrushed(*m.kv_rpm_per_v))
                             : 0.0;
          p.ke_v_s_per_rad = Get(e, "ke_v_s_per_rad", ke_from_kv);
          // Section 5: ideal waveforms give KT = sqrt(27/10)*KE; a DC machine KT = KE (SI).
          p.kt_nm_per_a = Get(e, "kt_nm_per_a", p.type == MotorType::kBldc
                                                    ? kPacPerVllIrms * p.ke_v_s_per_rad
                                                    : p.ke_v_s_per_rad);
          p.rm_ohm = e["rm_ohm"].get<double>();
          p.io_a = e["io_a"].get<double>();
          p.max_current_a = Get(e, "max_current_a", p.max_current_a);
          p.max_power_w = Get(e, "max_power_w", p.max_power_w);
          m.mass_kg = GetOpt(e, "mass_kg");
          index_[id] = {kind, motors_.size()};
          motors_.push_back(std::move(m));
          break;
        }
        case ComponentKind::kEsc: {
          EscEntry x;
          static_cast<EntryBase&>(x) = std::move(base);
          EscParams& p = x.params;
          p.resc_ohm = e["resc_ohm"].get<double>();
          p.c1 = e["c1"].get<double>();
          p.c0 = e["c0"].get<double>();
          p.tr_sat = e["tr_sat"].get<double>();
          p.sat_slope = e["sat_slope"].get<double>();
          p.max_current_a = Get(e, "max_current_a", p.max_current_a);
          p.vdc_max_v = Get(e, "vdc_max_v", p.vdc_max_v);
          x.mass_kg = GetOpt(e, "mass_kg");
          index_[id] = {kind, escs_.size()};
          escs_.push_back(std::move(x));
          break;
        }
        case ComponentKind::kProp: {
          PropEntry x;
          static_cast<EntryBase&>(x) = std::move(base);
          x.diameter_m = e["diameter_m"].get<double>();
          x.pitch_m = GetOpt(e, "pitch_m");
          x.mass_kg = GetOpt(e, "mass_kg");
          index_[id] = {kind, props_.size()};
          props_.push_back(std::move(x));
          break;
        }
        case ComponentKind::kBattery: {
          BatteryEntry x;
          static_cast<EntryBase&>(x) = std::move(base);
          x.mass_kg = GetOpt(e, "mass_kg");
          index_[id] = {kind, batteries_.size()};
          batteries_.push_back(std::move(x));
          break;
        }
      }
    }
  }
}

namespace {

std::vector<std::string> CatalogFiles(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw NoInputError(dir + ": no such catalog folder");
  std::vector<std::string> files;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::end(it);
       it.increment(ec)) {
    if (it->is_regular_file() && it->path().extension() == ".json") {
      files.push_back(it->path().string());
    }
  }
  if (ec) throw NoInputError(dir + ": cannot list the catalog folder: " + ec.message());
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace

std::vector<std::string> Catalog::Validate(const std::string& dir) {
  Catalog catalog;
  std::vector<std::string> problems;
  for (const auto& file : CatalogFiles(dir)) {
    try {
      catalog.AddDocument(ReadJsonFile(file), file, &problems);
    } catch (const DataError& e) {
      problems.push_back(e.what());
    }
  }
  return problems;
}

Catalog Catalog::Load(const std::string& dir) {
  Catalog catalog;
  std::vector<std::string> problems;
  const auto files = CatalogFiles(dir);
  if (files.empty()) throw DataError(dir + ": the catalog folder holds no .json file");
  for (const auto& file : files) {
    try {
      catalog.AddDocument(ReadJsonFile(file), file, &problems);
    } catch (const DataError& e) {
      problems.push_back(e.what());
    }
  }
  if (!problems.empty()) {
    std::ostringstream msg;
    for (std::size_t i = 0; i < problems.size() && i < kMaxProblemsInError; ++i) {
      msg << (i ? "\n" : "") << problems[i];
    }
    if (problems.size() > kMaxProblemsInError) {
      msg << "\n(and " << problems.size() - kMaxProblemsInError
          << " more; run 'dynosize catalog validate " << dir << "' for all)";
    }
    throw DataError(msg.str());
  }
  return catalog;
}

template <typename Entry>
const Entry& Catalog::Find(const std::vector<Entry>& entries, ComponentKind kind,
                           const std::string& id) const {
  const auto it = index_.find(id);
  if (it != index_.end() && it->second.first == kind) return entries[it->second.second];
  std::string msg = std::string("unknown ") + KindNoun(kind) + " id '" + id + "'";
  if (it != index_.end()) {
    msg += ": that id is a " + std::string(KindNoun(it->second.first));
  } else if (!entries.empty()) {
    std::vector<std::pair<std::size_t, std::string>> near;
    for (const auto& e : entries) near.emplace_back(EditDistance(id, e.id), e.id);
    const std::size_t k = std::min<std::size_t>(3, near.size());
    std::partial_sort(near.begin(), near.begin() + static_cast<std::ptrdiff_t>(k), near.end());
    msg += "; closest: ";
    for (std::size_t i = 0; i < k; ++i) msg += (i ? ", " : "") + near[i].second;
    msg += " (see 'dynosize catalog list --kind " + std::string(KindArrayName(kind)) + "')";
  } else {
    msg += std::string(": the catalog has no ") + KindArrayName(kind);
  }
  throw UsageError(msg);
}

const MotorEntry& Catalog::motor(const std::string& id) const {
  return Find(motors_, ComponentKind::kMotor, id);
}
const EscEntry& Catalog::esc(const std::string& id) const {
  return Find(escs_, ComponentKind::kEsc, id);
}
const PropEntry& Catalog::prop(const std::string& id) const {
  return Find(props_, ComponentKind::kProp, id);
}
const BatteryEntry& Catalog::battery(const std::string& id) const {
  return Find(batteries_, ComponentKind::kBattery, id);
}

}  // namespace dynosize
