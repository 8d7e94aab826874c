#include "importers/kde_sheets.h"

#include <cmath>
#include <map>
#include <sstream>

#include "common/error.h"
#include "common/numbers.h"
#include "common/units.h"
#include "importers/csv.h"

namespace dynosize {

namespace {

// The leading number of a printed value ("105 RPM/V" -> 105, "1075 g (1180 g ...)" -> 1075).
double LeadingNumber(const CsvTable& t, const CsvRow& row, std::size_t col) {
  const std::string f = t.Field(row, col);
  std::istringstream in(f);
  std::string token;
  in >> token;
  const auto v = ParseNumber(token);
  if (!v || !(*v > 0.0)) {
    throw DataError(t.Where(row) + ": column '" + t.header[col] + "' = '" + f +
                    "': must start with a positive number");
  }
  return *v;
}

double Number(const CsvTable& t, const CsvRow& row, std::size_t col, bool allow_empty) {
  const std::string f = t.Field(row, col);
  if (f.empty() && allow_empty) return kNaN;
  const auto v = ParseNumber(f);
  if (!v) throw DataError(t.Where(row) + ": column '" + t.header[col] + "' = '" + f + "': not a number");
  return *v;
}

}  // namespace

bool KdeSheetMotor::has_torque() const {
  for (const auto& r : rows) {
    if (std::isfinite(r.torque_nm)) return true;
  }
  return false;
}

std::vector<KdeSheetMotor> ReadKdeSheets(const std::string& dir) {
  const CsvTable specs = ReadCsv(dir + "/kde_motor_specs.csv");
  std::vector<KdeSheetMotor> motors;
  std::map<std::string, std::size_t> index;
  {
    const std::size_t c_name = specs.Column("motor"), c_kv = specs.Column("Kv"),
                      c_kt = specs.Column("Kt"), c_io = specs.Column("Io"), c_r = specs.Column("Rm"),
                      c_m = specs.Column("weight"), c_i = specs.Column("max_cont_current");
    for (const auto& row : specs.rows) {
      KdeSheetMotor m;
      m.name = specs.Field(row, c_name);
      m.kv_rpm_per_v = LeadingNumber(specs, row, c_kv);
      m.kt_nm_per_a = LeadingNumber(specs, row, c_kt);
      m.io_dc_a = LeadingNumber(specs, row, c_io);
      m.r_dc_ohm = LeadingNumber(specs, row, c_r);
      m.mass_kg = LeadingNumber(specs, row, c_m) * 1e-3;  // printed in g
      m.max_current_a = LeadingNumber(specs, row, c_i);
      index[m.name] = motors.size();
      motors.push_back(std::move(m));
    }
  }
  const CsvTable perf = ReadCsv(dir + "/kde_performance.csv");
  const std::size_t c_motor = perf.Column("motor"), c_block = perf.Column("block"),
                    c_v = perf.Column("V_from_P_over_I"), c_prop = perf.Column("prop_in"),
                    c_blades = perf.Column("prop_blades"), c_tr = perf.Column("throttle_pct"),
                    c_i = perf.Column("current_A"), c_rpm = perf.Column("rpm"),
                    c_q = perf.Column("torque_Nm"), c_t = perf.Column("thrust_N"),
                    c_tsl = perf.Column("thrust_sealevel_est_g");
  for (const auto& row : perf.rows) {
    const std::string name = perf.Field(row, c_motor);
    const auto it = index.find(name);
    if (it == index.end()) {
      throw DataError(perf.Where(row) + ": motor '" + name + "' has no row in kde_motor_specs.csv");
    }
    KdeSheetRow r;
    r.line = static_cast<int>(row.line);
    r.block = static_cast<int>(Number(perf, row, c_block, false));
    r.vdc_v = Number(perf, row, c_v, false);
    r.throttle = Number(perf, row, c_tr, false) / 100.0;  // printed in %
    r.idc_a = Number(perf, row, c_i, false);
    r.rpm = Number(perf, row, c_rpm, false);
    r.torque_nm = Number(perf, row, c_q, true);
    r.thrust_n = Number(perf, row, c_t, false);
    r.thrust_sealevel_est_n = GramForceToNewton(Number(perf, row, c_tsl, true));
    r.prop = perf.Field(row, c_prop) + " " + perf.Field(row, c_blades);
    motors[it->second].rows.push_back(std::move(r));
  }
  return motors;
}

}  // namespace dynosize
