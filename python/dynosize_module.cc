// The Python module _dynosize (re-exported by the package python/dynosize): the library's commands
// (src/api) with keyword arguments named like the CLI's flags, numpy arrays in and out, and the
// library's errors as Python exceptions carrying the CLI's message (docs/python.md).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "api/calibrate.h"
#include "api/catalog_json.h"
#include "api/diagnose.h"
#include "api/mission_catalog.h"
#include "api/mission_run.h"
#include "api/simulate.h"
#include "catalog/catalog.h"
#include "catalog/catalog_path.h"
#include "common/error.h"
#include "mission/mission.h"
#include "report/mission_report.h"
#include "report/point_json.h"
#include "report/sweep_report.h"
#include "study/sweep.h"

namespace py = pybind11;
using dynosize::Json;

namespace {

// A catalog loaded once and passed to every call (catalog=...): its folders and the loaded entries.
class PyCatalog {
 public:
  PyCatalog(std::optional<std::string> base, std::vector<std::string> added, bool override_ids) {
    folders_ = dynosize::ResolveCatalogFolders(base.value_or(""), added, override_ids);
    Reload();
  }
  // A folder of the user's own parts on top (as --catalog-add; override_ids as --override).
  PyCatalog& Add(const std::string& folder, bool override_ids) {
    dynosize::CatalogFolders next = folders_;
    next.added.push_back(folder);
    next.override_ids = next.override_ids || override_ids;
    auto loaded = std::make_shared<const dynosize::Catalog>(dynosize::Catalog::Load(next));
    folders_ = next;
    catalog_ = loaded;
    return *this;
  }
  const dynosize::Catalog& get() const { return *catalog_; }
  const dynosize::CatalogFolders& folders() const { return folders_; }

 private:
  void Reload() { catalog_ = std::make_shared<const dynosize::Catalog>(dynosize::Catalog::Load(folders_)); }
  dynosize::CatalogFolders folders_;
  std::shared_ptr<const dynosize::Catalog> catalog_;
};

// The bundled catalog, loaded on first use (the default of every catalog= argument).
const PyCatalog& CatalogOr(const PyCatalog* given) {
  if (given != nullptr) return *given;
  static std::unique_ptr<PyCatalog> bundled;
  if (!bundled) bundled = std::make_unique<PyCatalog>(std::nullopt, std::vector<std::string>{}, false);
  return *bundled;
}

// nlohmann::json -> Python objects (dict, list, str, float, int, bool, None).
py::object ToPython(const Json& j) {
  switch (j.type()) {
    case Json::value_t::object: {
      py::dict d;
      for (auto it = j.begin(); it != j.end(); ++it) d[py::str(it.key())] = ToPython(it.value());
      return std::move(d);
    }
    case Json::value_t::array: {
      py::list l;
      for (const auto& v : j) l.append(ToPython(v));
      return std::move(l);
    }
    case Json::value_t::string: return py::str(j.get<std::string>());
    case Json::value_t::boolean: return py::bool_(j.get<bool>());
    case Json::value_t::number_integer: return py::int_(j.get<long long>());
    case Json::value_t::number_unsigned: return py::int_(j.get<unsigned long long>());
    case Json::value_t::number_float: return py::float_(j.get<double>());
    default: return py::none();
  }
}

// A document for Python, after the same finiteness check as the CLI's output (common/json_file.h
// DumpJson): a non-finite number is a bug (InternalError -> dynosize.Error), never returned.
py::object Result(const Json& j, const std::string& what) {
  dynosize::CheckJsonFinite(j, what);
  return ToPython(j);
}

// A mission given as a file path or as a dict (the mission JSON's content).
dynosize::Mission MissionOf(const py::object& mission) {
  if (py::isinstance<py::dict>(mission)) {
    const std::string text = py::module_::import("json").attr("dumps")(mission).cast<std::string>();
    return dynosize::ParseMission(Json::parse(text), "<mission dict>");
  }
  return dynosize::ReadMission(py::str(mission).cast<std::string>());
}

// The columns of simulate(): scalars broadcast to the length of the arrays given.
using Column = std::optional<py::array_t<double, py::array::c_style | py::array::forcecast>>;

std::size_t BroadcastLength(const std::vector<std::pair<const char*, const Column*>>& cols) {
  std::size_t n = 1;
  for (const auto& [name, c] : cols) {
    if (!*c || (*c)->ndim() == 0 || (*c)->size() == 1) continue;
    if ((*c)->ndim() != 1) throw dynosize::UsageError(std::string(name) + ": give a number or a 1-D array");
    const auto m = static_cast<std::size_t>((*c)->size());
    if (n != 1 && m != n) {
      throw dynosize::UsageError(std::string(name) + ": " + std::to_string(m) + " values where the other arrays have " +
                                 std::to_string(n));
    }
    n = m;
  }
  return n;
}

// A column as the batch reads it (api/simulate.h BatchColumn): its numpy memory, one value
// broadcast or n values.
dynosize::api::BatchColumn ColumnOf(const Column& c) {
  if (!c) return {};
  return {c->data(), c->size() == 1};
}

// simulate(): the batch path over arrays (api::SimulateColumns, the model's structure-of-arrays
// batch of model/drive_batch.h), written straight into the numpy arrays it returns: one array per
// key of the point JSON (report/point_json.h), allocated once and filled in place.
py::dict Simulate(const std::string& motor_id, const std::string& esc_id, const Column& vdc_v, const Column& throttle,
                  const Column& torque_nm, const Column& rpm, const std::string& prop, const Column& thrust_n,
                  const PyCatalog* catalog) {
  if (!vdc_v) throw dynosize::UsageError("--vdc is required (supply voltage, V)");
  const std::size_t n = BroadcastLength(
      {{"vdc_v", &vdc_v}, {"throttle", &throttle}, {"torque_nm", &torque_nm}, {"rpm", &rpm}, {"thrust_n", &thrust_n}});
  const dynosize::Catalog& cat = CatalogOr(catalog).get();
  const dynosize::MotorEntry& motor = cat.motor(motor_id);
  const dynosize::EscEntry& esc = cat.esc(esc_id);
  const auto size = static_cast<py::ssize_t>(n);
  py::dict out;
  // The number columns are the rows of one C-contiguous (k, n) block, each returned as its own
  // 1-D array (a view that keeps the block alive): one allocation instead of 16 to 18. Freed and
  // allocated again call after call, one block of this size is reused by the C library's
  // allocator, where 16 separate ones are handed back to the kernel and every page of them is
  // faulted in again (docs/python.md, "Performance").
  const py::ssize_t count = prop.empty() ? 16 : 18;
  py::array_t<double> block({count, size});
  double* next = block.mutable_data();
  const auto number = [&](const char* key) {
    double* column = next;
    next += n;
    out[key] = py::array_t<double>({size}, {static_cast<py::ssize_t>(sizeof(double))}, column, block);
    return column;
  };
  dynosize::PointColumns c;
  c.vdc_v = number("vdc_v");
  c.throttle = number("throttle");
  c.throttle_effective = number("throttle_effective");
  c.rpm = number("rpm");
  c.omega_rad_s = number("omega_rad_s");
  c.torque_nm = number("torque_nm");
  c.irms_a = number("irms_a");
  c.vll_rms_v = number("vll_rms_v");
  c.pac_w = number("pac_w");
  c.idc_a = number("idc_a");
  c.pdc_w = number("pdc_w");
  c.pesc_w = number("pesc_w");
  c.pmech_w = number("pmech_w");
  c.eta_motor = number("eta_motor");
  c.eta_esc = number("eta_esc");
  c.eta_system = number("eta_system");
  py::array_t<bool> saturated(size), feasible(size);
  c.saturated = saturated.mutable_data();
  c.feasible = feasible.mutable_data();
  // The Limit bits, named below once per distinct code: scratch kept by the thread from call to
  // call (never returned).
  static thread_local std::vector<std::uint32_t> codes;
  codes.resize(n);
  c.limits = codes.data();
  dynosize::api::PropColumns pc;
  std::unique_ptr<bool[]> beats;
  if (!prop.empty()) {
    pc.thrust_n = number("thrust_n");
    pc.g_per_w = number("g_per_w");
    beats.reset(new bool[n]());
    pc.beats_momentum_theory = beats.get();
  }
  dynosize::api::BatchColumns in;
  in.n = n;
  in.vdc_v = ColumnOf(vdc_v);
  in.throttle = ColumnOf(throttle);
  in.torque_nm = ColumnOf(torque_nm);
  in.rpm = ColumnOf(rpm);
  in.thrust_n = ColumnOf(thrust_n);
  in.prop = prop;
  const dynosize::Drive drive(motor.params, esc.params);
  {
    py::gil_scoped_release release;  // no Python object is touched while the points are solved
    dynosize::api::SimulateColumns(cat, drive, in, "simulate: point", c, pc);
  }
  // "limits": the names joined with ';' (as the --batch CSV's column), one str per distinct code
  // shared by the points that have it; a propeller that beats momentum theory adds its name and
  // makes the point infeasible (as the CLI's JSON).
  py::array limits(py::dtype("O"), std::vector<py::ssize_t>{size});
  auto* lim = static_cast<PyObject**>(limits.mutable_data());
  // Each name is looked up by its code in a table (the Limit bits are 10, model/drive.h; the
  // propeller's beats_momentum_theory is one more): a first pass counts the points per code, the
  // names are made for the codes present, and a second pass stores one pointer per point without
  // a branch; the references are added in bulk (an increment per point would chain every store
  // on one reference count).
  constexpr std::uint32_t kCodes = dynosize::kLimitCreatesEnergy << 1;
  std::vector<Py_ssize_t> uses(2 * kCodes, 0);
  for (std::size_t i = 0; i < n; ++i) {
    if (beats && beats[i]) {
      c.feasible[i] = false;
      codes[i] += kCodes;
    }
    ++uses[codes[i]];
  }
  std::vector<py::object> texts(2 * kCodes);  // null where no point has the code
  std::vector<PyObject*> text_of(2 * kCodes, nullptr);
  for (std::uint32_t k = 0; k < 2 * kCodes; ++k) {
    if (uses[k] == 0) continue;
    std::string joined;
    for (const auto& name : dynosize::api::BatchLimitNames(k % kCodes, k >= kCodes)) {
      joined += (joined.empty() ? "" : ";") + name;
    }
    texts[k] = py::str(joined);
    text_of[k] = texts[k].ptr();
#if PY_VERSION_HEX >= 0x03090000
    Py_SET_REFCNT(text_of[k], Py_REFCNT(text_of[k]) + uses[k]);
#else
    for (Py_ssize_t r = 0; r < uses[k]; ++r) Py_INCREF(text_of[k]);
#endif
  }
  for (std::size_t i = 0; i < n; ++i) lim[i] = text_of[codes[i]];  // a new object array holds NULLs
  out["saturated"] = saturated;
  out["feasible"] = feasible;
  out["limits"] = limits;
  return out;
}

py::object Evaluate(const py::object& mission_arg, const std::string& motor, const std::string& esc,
                    const std::string& prop, const std::string& battery, const std::vector<std::string>& pick,
                    int cells, const PyCatalog* catalog) {
  const dynosize::Mission mission = MissionOf(mission_arg);
  const dynosize::api::MissionCatalog mission_catalog(CatalogOr(catalog).get(), mission);
  const dynosize::Catalog& cat = mission_catalog.get();
  const dynosize::Combination c = dynosize::api::ChooseCombination(mission, cat, {motor, esc, prop, battery, pick, cells});
  dynosize::MissionResult r;
  {
    py::gil_scoped_release release;
    r = dynosize::api::EvaluateCombination(mission, c);
  }
  return Result(dynosize::MissionResultJson(mission, c, r), "evaluate result");
}

py::object Optimize(const py::object& mission_arg, int top, int threads, bool variants, double time_limit_s,
                    const PyCatalog* catalog) {
  if (top < 1 || top > 1000) throw dynosize::UsageError("--top " + std::to_string(top) + ": must be in [1 - 1000]");
  if (threads < 1 || threads > 64) {
    throw dynosize::UsageError("--threads " + std::to_string(threads) + ": must be in [1 - 64]");
  }
  dynosize::SearchOptions so = dynosize::api::OptimizeSearchOptions({top, threads, variants, time_limit_s});
  const dynosize::Mission mission = MissionOf(mission_arg);
  const dynosize::api::MissionCatalog mission_catalog(CatalogOr(catalog).get(), mission);
  const dynosize::Catalog& cat = mission_catalog.get();
  dynosize::SearchResult s;
  {
    py::gil_scoped_release release;
    s = dynosize::SearchCatalog(mission, cat, so);
  }
  return Result(dynosize::SearchResultJson(mission, s), "optimize result");
}

dynosize::api::LogInputOptions LogInput(const std::string& format, const std::vector<std::string>& column_map,
                                        bool drop_incomplete_rows, bool decimal_comma,
                                        const std::vector<std::string>& where, double esc_min_us, double esc_max_us) {
  return {format, column_map, drop_incomplete_rows, decimal_comma, where, esc_min_us, esc_max_us};
}

// sweep(): the plan travels as a plain dict (a distributed study pickles it to every task):
// the mission document and the keys as JSON text, its name and the grid's size.
py::dict PlanDict(const dynosize::study::SweepPlan& plan) {
  Json keys = Json::array();
  for (const auto& k : plan.keys) keys.push_back({{"key", k.key}, {"values", k.values}});
  py::dict d;
  d["mission_json"] = plan.doc.dump();
  d["name"] = plan.name;
  d["keys_json"] = keys.dump();
  d["points"] = plan.points;
  return d;
}

dynosize::study::SweepPlan PlanOf(const py::dict& d) {
  dynosize::study::SweepPlan plan;
  plan.doc = Json::parse(d["mission_json"].cast<std::string>());
  plan.name = d["name"].cast<std::string>();
  for (const Json& k : Json::parse(d["keys_json"].cast<std::string>())) {
    plan.keys.push_back({k.at("key").get<std::string>(), k.at("values").get<std::vector<Json>>()});
  }
  plan.points = d["points"].cast<std::size_t>();
  return plan;
}

// grid: {KEY: "START:STOP:STEP" or "v1,v2" (as --vary), or a list of values}.
py::dict SweepPlanOf(const py::object& mission, const py::dict& grid, bool yes) {
  Json doc;
  std::string name = "<mission dict>";
  const py::module_ json = py::module_::import("json");
  if (py::isinstance<py::dict>(mission)) {
    doc = Json::parse(json.attr("dumps")(mission).cast<std::string>());
  } else {
    name = py::str(mission).cast<std::string>();
    doc = dynosize::ReadJsonFile(name);
  }
  std::vector<dynosize::study::VaryKey> keys;
  for (const auto& [k, v] : grid) {
    const std::string key = py::str(k).cast<std::string>();
    if (py::isinstance<py::str>(v)) {
      keys.push_back(dynosize::study::ParseVary(key + "=" + v.cast<std::string>()));
    } else {
      const Json values = Json::parse(json.attr("dumps")(py::list(py::reinterpret_borrow<py::object>(v))).cast<std::string>());
      if (values.empty()) throw dynosize::UsageError("grid['" + key + "']: give at least one value");
      keys.push_back({key, values.get<std::vector<Json>>()});
    }
  }
  return PlanDict(dynosize::study::PlanSweep(std::move(doc), std::move(name), std::move(keys), yes));
}

// One grid point, as a task of a distributed study runs it: the row of sweep --json.
py::object SweepPoint(const py::dict& plan_dict, std::size_t index, int top, bool variants, const PyCatalog* catalog) {
  const dynosize::study::SweepPlan plan = PlanOf(plan_dict);
  std::vector<dynosize::Mission> point;  // the point's own sized propellers (a point that does not parse: a failed row)
  try {
    point.push_back(dynosize::ParseMission(
        dynosize::study::MissionAt(plan.doc, plan.keys, dynosize::study::GridPoint(plan.keys, index)), plan.name));
  } catch (const dynosize::DataError&) {
  }
  const dynosize::api::MissionCatalog mission_catalog(CatalogOr(catalog).get(), point);
  const dynosize::Catalog& cat = mission_catalog.get();
  dynosize::study::PointOptions po;
  po.top = top;
  po.distinct_designs = !variants;
  Json row;
  {
    py::gil_scoped_release release;
    row = dynosize::study::SweepRowJson(dynosize::study::RunPoint(plan.doc, plan.name, cat, plan.keys, index, po),
                                        plan.keys);
  }
  return Result(row, "sweep row");
}

// Every point on this machine's threads: the dict of sweep --json.
py::object SweepLocal(const py::dict& plan_dict, int top, bool variants, int threads, const PyCatalog* catalog) {
  const dynosize::study::SweepPlan plan = PlanOf(plan_dict);
  const dynosize::api::MissionCatalog mission_catalog(CatalogOr(catalog).get(), dynosize::study::PointMissions(plan));
  const dynosize::Catalog& cat = mission_catalog.get();
  dynosize::study::SweepOptions so;
  so.point.top = top;
  so.point.distinct_designs = !variants;
  so.threads = threads;
  dynosize::study::SweepResult r;
  {
    py::gil_scoped_release release;
    r = dynosize::study::RunSweep(plan.doc, plan.name, cat, plan.keys, so);
  }
  return Result(dynosize::study::SweepJson(dynosize::ParseMission(plan.doc, plan.name), r, plan.keys), "sweep result");
}

// The document from rows gathered from a distributed study's tasks (in grid order).
py::object SweepDocumentOf(const py::dict& plan_dict, const py::list& rows, double seconds) {
  const dynosize::study::SweepPlan plan = PlanOf(plan_dict);
  const py::module_ json = py::module_::import("json");
  Json rows_json = Json::parse(json.attr("dumps")(rows).cast<std::string>());
  return Result(dynosize::study::SweepDocument(dynosize::ParseMission(plan.doc, plan.name), plan.keys, plan.points,
                                               std::move(rows_json), false, seconds),
                "sweep result");
}

void CheckSweepOptions(int top, int threads) {
  if (top < 1 || top > 1000) throw dynosize::UsageError("--top " + std::to_string(top) + ": must be in [1 - 1000]");
  if (threads < 1 || threads > 64) {
    throw dynosize::UsageError("--threads " + std::to_string(threads) + ": must be in [1 - 64]");
  }
}

// Errors: bad input -> ValueError, a missing file -> FileNotFoundError, the rest -> dynosize.Error
// (a RuntimeError); the message is the CLI's (without its "dynosize: " prefix).
void RegisterErrors(py::module_& m) {
  static py::exception<dynosize::Error> error(m, "Error", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const dynosize::UsageError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const dynosize::DataError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const dynosize::NoInputError& e) {
      PyErr_SetString(PyExc_FileNotFoundError, e.what());
    } catch (const dynosize::Error& e) {
      error(e.what());
    } catch (const Json::exception& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });
}

// dynosize.Catalog and the catalog folders.
void BindCatalog(py::module_& m) {
  py::class_<PyCatalog>(m, "Catalog", "The component catalog, loaded once and passed as catalog=...")
      .def(py::init<std::optional<std::string>, std::vector<std::string>, bool>(), py::arg("path") = py::none(),
           py::arg("add") = std::vector<std::string>{}, py::arg("override") = false,
           "Load the bundled catalog (or the folder path; $DYNOSIZE_CATALOG), then the folders of "
           "$DYNOSIZE_CATALOG_PATH and add (as --catalog, --catalog-add, --override)")
      .def("add", &PyCatalog::Add, py::arg("folder"), py::arg("override") = false, py::return_value_policy::reference,
           "Read a folder of your own parts on top (as --catalog-add); an id the catalog holds is an error "
           "unless override=True")
      .def(
          "list",
          [](const PyCatalog& c, std::optional<std::string> kind, std::optional<double> kv_min,
             std::optional<double> kv_max, std::optional<double> mass_max_kg, std::optional<double> current_min_a) {
            const dynosize::api::CatalogListRequest r{kind.value_or(""), kv_min, kv_max, mass_max_kg, current_min_a};
            if (!r.kind.empty() && r.kind != "motors" && r.kind != "escs" && r.kind != "props" && r.kind != "batteries") {
              throw dynosize::UsageError("--kind " + r.kind + ": not in {motors, escs, props, batteries}");
            }
            dynosize::api::CheckCatalogListRequest(r);
            const Json j = dynosize::api::CatalogListJson(c.get(), r);
            return r.kind.empty() ? Result(j, "catalog list") : Result(j[r.kind], "catalog list");
          },
          py::arg("kind") = py::none(), py::arg("kv_min") = py::none(), py::arg("kv_max") = py::none(),
          py::arg("mass_max_kg") = py::none(), py::arg("current_min_a") = py::none(),
          "The entries as catalog list --json: {kind: [entries]}, or the list of one kind")
      .def(
          "show", [](const PyCatalog& c, const std::string& id) { return Result(dynosize::api::CatalogShowJson(c.get(), id), "catalog show"); },
          py::arg("id"), "One entry with its derived SI parameters (catalog show)")
      .def_property_readonly("folders",
                             [](const PyCatalog& c) {
                               std::vector<std::string> f{c.folders().base};
                               f.insert(f.end(), c.folders().added.begin(), c.folders().added.end());
                               return f;
                             })
      .def_property_readonly("_spec",
                             [](const PyCatalog& c) {
                               return py::make_tuple(c.folders().base, c.folders().added, c.folders().override_ids);
                             })
      .def("__len__", [](const PyCatalog& c) { return c.get().size(); });

  m.def("bundled_catalog_dir", &dynosize::BundledCatalogDir, "The folder of the bundled catalog");
  m.def("_set_package_catalog_dir", &dynosize::SetPackageCatalogDir,
        "The installed package's catalog (set by the package's __init__ when installed)");
}

// The commands: simulate, evaluate, optimize, calibrate, diagnose.
void BindCommands(py::module_& m) {
  m.def("simulate", &Simulate, py::kw_only(), py::arg("motor"), py::arg("esc"), py::arg("vdc_v") = py::none(),
        py::arg("throttle") = py::none(), py::arg("torque_nm") = py::none(), py::arg("rpm") = py::none(),
        py::arg("prop") = "", py::arg("thrust_n") = py::none(), py::arg("catalog") = nullptr,
        "Operating points of a motor + ESC (+ propeller) pair through the batch path of simulate --batch: "
        "scalars or 1-D arrays (broadcast); a dict of numpy arrays with the CLI's JSON keys");
  m.def("evaluate", &Evaluate, py::arg("mission"), py::kw_only(), py::arg("motor") = "", py::arg("esc") = "",
        py::arg("prop") = "", py::arg("battery"), py::arg("pick") = std::vector<std::string>{}, py::arg("cells") = 0,
        py::arg("catalog") = nullptr, "One combination flying a mission: the dict of evaluate --json");
  m.def("optimize", &Optimize, py::arg("mission"), py::kw_only(), py::arg("top") = 5, py::arg("threads") = 2,
        py::arg("variants") = false, py::arg("time_limit_s") = std::numeric_limits<double>::infinity(),
        py::arg("catalog") = nullptr, "The best combinations of the catalog: the dict of optimize --json");
  m.def(
      "calibrate",
      [](const std::vector<std::string>& logs, const std::string& motor_id, const std::string& esc_id,
         const std::string& format, const std::vector<std::string>& column_map, bool drop_incomplete_rows,
         bool decimal_comma, const std::vector<std::string>& where, double esc_min_us, double esc_max_us,
         long long drivecalc_motor, const std::string& prior_motor, const std::string& prior_esc, bool loo,
         std::optional<double> kv_label, std::optional<double> rm_label, std::optional<double> io_label,
         std::optional<double> io_label_v, std::optional<double> mass_kg, std::optional<double> max_current_a,
         std::optional<double> max_power_w, std::optional<double> esc_max_current_a,
         std::optional<double> esc_vdc_max_v, std::optional<double> esc_mass_kg, const std::string& prop_id,
         std::optional<double> prop_diameter_in, std::optional<double> prop_pitch_in, const PyCatalog* catalog) {
        const dynosize::api::CalibrateRequest r{
            logs, motor_id, esc_id,
            LogInput(format, column_map, drop_incomplete_rows, decimal_comma, where, esc_min_us, esc_max_us),
            drivecalc_motor, prior_motor, prior_esc, loo, kv_label, rm_label, io_label, io_label_v, mass_kg,
            max_current_a, max_power_w, esc_max_current_a, esc_vdc_max_v, esc_mass_kg, prop_id, prop_diameter_in,
            prop_pitch_in};
        const bool priors = !prior_motor.empty() || !prior_esc.empty();
        const dynosize::Catalog* cat = priors ? &CatalogOr(catalog).get() : nullptr;
        Json j;
        {
          py::gil_scoped_release release;
          j = dynosize::api::CalibrateLogs(r, cat);
        }
        return Result(j, "calibrate result");
      },
      py::arg("logs"), py::kw_only(), py::arg("motor_id"), py::arg("esc_id"), py::arg("format") = "auto",
      py::arg("map") = std::vector<std::string>{}, py::arg("drop_incomplete_rows") = false,
      py::arg("decimal_comma") = false, py::arg("where") = std::vector<std::string>{}, py::arg("esc_min_us") = 1000.0,
      py::arg("esc_max_us") = 2000.0, py::arg("drivecalc_motor") = -1, py::arg("prior_motor") = "",
      py::arg("prior_esc") = "", py::arg("loo") = false, py::arg("kv_label") = py::none(),
      py::arg("rm_label") = py::none(), py::arg("io_label") = py::none(), py::arg("io_label_v") = py::none(),
      py::arg("mass_kg") = py::none(), py::arg("max_current_a") = py::none(), py::arg("max_power_w") = py::none(),
      py::arg("esc_max_current_a") = py::none(), py::arg("esc_vdc_max_v") = py::none(),
      py::arg("esc_mass_kg") = py::none(), py::arg("prop_id") = "", py::arg("prop_diameter_in") = py::none(),
      py::arg("prop_pitch_in") = py::none(), py::arg("catalog") = nullptr,
      "Fit motor + ESC entries to logs: the dict of calibrate --json (nothing written)");
  m.def(
      "diagnose",
      [](const std::string& log, const std::string& motor, const std::string& esc, const std::string& format,
         const std::vector<std::string>& column_map, bool drop_incomplete_rows, bool decimal_comma,
         const std::vector<std::string>& where, double esc_min_us, double esc_max_us, int folds, double alpha,
         std::optional<double> kv_label, const PyCatalog* catalog) {
        const dynosize::api::DiagnoseRequest r{
            log, motor, esc,
            LogInput(format, column_map, drop_incomplete_rows, decimal_comma, where, esc_min_us, esc_max_us), folds,
            alpha, kv_label};
        dynosize::api::CheckDiagnoseRequest(r);
        const dynosize::Catalog* cat = (!motor.empty() || !esc.empty()) ? &CatalogOr(catalog).get() : nullptr;
        Json j;
        {
          py::gil_scoped_release release;
          j = dynosize::api::DiagnoseLog(r, cat);
        }
        return Result(j, "diagnose result");
      },
      py::arg("log"), py::kw_only(), py::arg("motor") = "", py::arg("esc") = "", py::arg("format") = "auto",
      py::arg("map") = std::vector<std::string>{}, py::arg("drop_incomplete_rows") = false,
      py::arg("decimal_comma") = false, py::arg("where") = std::vector<std::string>{}, py::arg("esc_min_us") = 1000.0,
      py::arg("esc_max_us") = 2000.0, py::arg("folds") = 5, py::arg("alpha") = 1e-3, py::arg("kv_label") = py::none(),
      py::arg("catalog") = nullptr, "What the model gets wrong in a measured log: the dict of diagnose --json");
}

// The trade study (python/dynosize/__init__.py sweep: local, or one task per point on a dask cluster).
void BindSweep(py::module_& m) {
  m.def("_sweep_plan", &SweepPlanOf, py::arg("mission"), py::arg("grid"), py::arg("yes") = false,
        "The sweep's plan (mission, keys, grid size), checked as the CLI checks --vary");
  m.def(
      "_sweep_point",
      [](const py::dict& plan, std::size_t index, int top, bool variants, const PyCatalog* catalog) {
        CheckSweepOptions(top, 1);
        return SweepPoint(plan, index, top, variants, catalog);
      },
      py::arg("plan"), py::arg("index"), py::kw_only(), py::arg("top") = 1, py::arg("variants") = false,
      py::arg("catalog") = nullptr, "One grid point's row of sweep --json");
  m.def(
      "_sweep_local",
      [](const py::dict& plan, int top, bool variants, int threads, const PyCatalog* catalog) {
        CheckSweepOptions(top, threads);
        return SweepLocal(plan, top, variants, threads, catalog);
      },
      py::arg("plan"), py::kw_only(), py::arg("top") = 1, py::arg("variants") = false, py::arg("threads") = 2,
      py::arg("catalog") = nullptr, "Every grid point on this machine: the dict of sweep --json");
  m.def("_sweep_document", &SweepDocumentOf, py::arg("plan"), py::arg("rows"), py::arg("seconds"),
        "The dict of sweep --json from rows gathered in grid order");
}

}  // namespace

PYBIND11_MODULE(_dynosize, m) {
  m.doc() = "dynosize: motor + ESC model, catalog, calibration and sizing (docs/python.md)";
  m.attr("__version__") = DYNOSIZE_VERSION;

  RegisterErrors(m);
  BindCatalog(m);
  BindCommands(m);
  BindSweep(m);
}
