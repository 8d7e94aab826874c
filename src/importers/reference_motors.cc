#include "importers/reference_motors.h"

#include <cmath>

#include "common/error.h"
#include "importers/csv.h"

namespace dynosize {
namespace {

// A number of column `name`: NaN when the field is empty, DataError when it is not a number.
double Cell(const CsvTable& t, const CsvRow& row, const std::string& name, double scale = 1.0) {
  const std::size_t col = t.Column(name);
  const std::string f = t.Field(row, col);
  if (f.empty()) return kNotStated;
  const auto v = ParseNumber(f);
  if (!v) throw DataError(t.Where(row) + ": column '" + name + "' = '" + f + "': not a number");
  if (*v < 0.0) throw DataError(t.Where(row) + ": column '" + name + "' = '" + f + "': negative");
  return *v * scale;
}

// A constant that must be stated in every row of its file.
double Required(const CsvTable& t, const CsvRow& row, const std::string& name) {
  const double v = Cell(t, row, name);
  if (!(v > 0.0)) {
    throw DataError(t.Where(row) + ": column '" + name + "' = '" + t.Field(row, t.Column(name)) +
                    "': must be a number > 0");
  }
  return v;
}

// 0 (a rounded-away or placeholder value) is not a statement.
double PositiveOrNaN(double v) { return v > 0.0 ? v : kNotStated; }

// The NeuMotors sheets print R and Io with 3 decimals: below 0.010 the rounding exceeds 5 %.
constexpr double kNeuMotorsSmallestUsable = 0.010;

StatedMotor EvtolStated(const CsvTable& t, const CsvRow& row) {
  StatedMotor s;
  s.maker = t.Field(row, t.Column("maker"));
  s.model = t.Field(row, t.Column("model"));
  s.mass_kg = PositiveOrNaN(Cell(t, row, "mass_kg"));
  s.p_cont_w = PositiveOrNaN(Cell(t, row, "p_cont_kw", 1e3));
  s.p_peak_w = PositiveOrNaN(Cell(t, row, "p_peak_kw", 1e3));
  s.t_cont_nm = PositiveOrNaN(Cell(t, row, "t_cont_nm"));
  s.t_peak_nm = PositiveOrNaN(Cell(t, row, "t_peak_nm"));
  s.rpm_max = PositiveOrNaN(Cell(t, row, "rpm_max"));
  s.rpm_rated = PositiveOrNaN(Cell(t, row, "rpm_rated"));
  s.v_nom_v = PositiveOrNaN(Cell(t, row, "v_nom_v"));
  s.v_max_v = PositiveOrNaN(Cell(t, row, "v_max_v"));
  s.kv_rpm_per_v = PositiveOrNaN(Cell(t, row, "kv_rpm_per_v"));
  return s;
}

}  // namespace

std::vector<ReferenceMotor> ReadEvtolReferenceMotors(const std::string& path) {
  const CsvTable t = ReadCsv(path);
  std::vector<ReferenceMotor> out;
  for (const auto& row : t.rows) {
    ReferenceMotor r;
    r.stated = EvtolStated(t, row);
    if (std::isnan(r.stated.kv_rpm_per_v)) continue;  // no constant: not a reference
    r.kv_rpm_per_v = r.stated.kv_rpm_per_v;
    r.stated.kv_rpm_per_v = kNotStated;
    // "measured phase to phase, then divided by 2": the line-to-line value is twice it.
    r.r_dc_ohm = PositiveOrNaN(Cell(t, row, "r_phase_ohm", 2.0));
    r.where = t.Where(row);
    out.push_back(r);
  }
  return out;
}

std::vector<ReferenceMotor> ReadNeuMotorsWindings(const std::string& path) {
  const CsvTable t = ReadCsv(path);
  std::vector<ReferenceMotor> out;
  for (const auto& row : t.rows) {
    ReferenceMotor r;
    r.stated.maker = "NeuMotors";
    r.stated.model = t.Field(row, t.Column("model"));
    r.stated.mass_kg = PositiveOrNaN(Cell(t, row, "model_mass_kg"));
    r.stated.p_cont_w = PositiveOrNaN(Cell(t, row, "model_p_cont_kw", 1e3));
    r.stated.p_peak_w = PositiveOrNaN(Cell(t, row, "model_p_peak_kw", 1e3));
    r.stated.rpm_max = PositiveOrNaN(Cell(t, row, "model_rpm_max"));
    // max_volts_v is rpm_max/Kv (the sheet's own division), not a stated voltage: left out so
    // that (E1) is not fitted on its own definition.
    r.kv_rpm_per_v = Required(t, row, "kv_rpm_per_v");
    double rm = Cell(t, row, "rm_ohm"), io = Cell(t, row, "io_a");
    if (t.Field(row, t.Column("flags")).rfind("88xx sheet: Rm rises", 0) == 0) std::swap(rm, io);
    r.r_dc_ohm = rm >= kNeuMotorsSmallestUsable ? rm : kNotStated;
    r.io_dc_a = io >= kNeuMotorsSmallestUsable ? io : kNotStated;
    r.io_test_v = Required(t, row, "io_test_v");
    r.where = t.Where(row);
    out.push_back(r);
  }
  return out;
}

std::vector<ReferenceMotor> ReadHeavyLiftMotors(const std::string& path) {
  const CsvTable t = ReadCsv(path);
  std::vector<ReferenceMotor> out;
  for (const auto& row : t.rows) {
    if (t.Field(row, t.Column("in_kde_datasheets")).rfind("yes", 0) == 0) continue;
    ReferenceMotor r;
    r.stated.maker = t.Field(row, t.Column("maker"));
    r.stated.model = t.Field(row, t.Column("model"));
    r.stated.mass_kg = Required(t, row, "mass_kg");
    r.stated.p_cont_w = PositiveOrNaN(Cell(t, row, "p_max_w"));
    r.stated.p_peak_w = PositiveOrNaN(Cell(t, row, "p_peak_w"));
    r.kv_rpm_per_v = Required(t, row, "kv_rpm_per_v");
    r.r_dc_ohm = Required(t, row, "r_ohm");
    r.io_dc_a = Required(t, row, "io_a");
    r.io_test_v = Required(t, row, "io_test_v");
    r.where = t.Where(row);
    out.push_back(r);
  }
  return out;
}

std::vector<ReferenceMotor> ReadKdeDatasheetMotors(const std::string& path) {
  const CsvTable t = ReadCsv(path);
  std::vector<ReferenceMotor> out;
  for (const auto& row : t.rows) {
    ReferenceMotor r;
    r.stated.maker = "KDE Direct";
    r.stated.model = t.Field(row, t.Column("motor"));
    r.stated.mass_kg = Required(t, row, "mass_kg");
    r.stated.p_cont_w = PositiveOrNaN(Cell(t, row, "p_max_w"));
    r.stated.v_max_v = PositiveOrNaN(Cell(t, row, "v_max_v"));
    r.kv_rpm_per_v = Required(t, row, "kv_rpm_per_v");
    r.r_dc_ohm = Required(t, row, "rm_ohm");
    r.io_dc_a = Required(t, row, "io_a");
    r.io_test_v = Required(t, row, "io_test_v");
    r.where = t.Where(row);
    out.push_back(r);
  }
  return out;
}

std::vector<ReferenceMotor> ReadReferenceMotors(const std::string& data_dir) {
  std::vector<ReferenceMotor> out = ReadEvtolReferenceMotors(data_dir + "/evtol_motors/evtol_motors.csv");
  for (auto more : {ReadNeuMotorsWindings(data_dir + "/evtol_motors/neumotors_windings.csv"),
                    ReadHeavyLiftMotors(data_dir + "/heavy_lift_motors/heavy_lift_motors.csv"),
                    ReadKdeDatasheetMotors(data_dir + "/heavy_lift_motors/kde_datasheets.csv")}) {
    out.insert(out.end(), more.begin(), more.end());
  }
  return out;
}

std::vector<EvtolStatedRow> ReadEvtolStatedMotors(const std::string& path) {
  const CsvTable t = ReadCsv(path);
  std::vector<EvtolStatedRow> out;
  for (const auto& row : t.rows) {
    EvtolStatedRow r;
    r.stated = EvtolStated(t, row);
    const std::string variant = t.Field(row, t.Column("variant"));
    if (!variant.empty()) r.stated.model += ", " + variant;
    r.where = t.Where(row);
    out.push_back(r);
  }
  return out;
}

}  // namespace dynosize
