// End-to-end tests of `simulate --prop` and `validate-stand`, and of simulate
// never calling a point that creates energy feasible.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <iterator>
#include <filesystem>
#include <fstream>

#include "cli_runner.h"
#include "common/json_file.h"
#include "common/units.h"

namespace dynosize {
namespace {

namespace fs = std::filesystem;
using testing_util::CliRun;
using testing_util::RunCli;

int Lines(const std::string& s) {
  int n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

// A catalog folder cat/ with one motor, one ESC and a propeller with a power law (so Q =
// k*omega^2): p, T = 0.2 N*(rpm/1000)^2, P = 0.42 W*(rpm/1000)^3 (figure of merit 0.60 at every
// speed); and badcat/ with the same plus an ESC that creates energy (c1 + c0 < 1.1095) and
// "hot", T = 2 N*(rpm/1000)^2, P = 1.5 W*(rpm/1000)^3 (figure of merit 5.3: beats momentum
// theory), which the catalog reader refuses (docs/model.md section 10).
class StandCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("dynosize_stand_cli_" + std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "cat");
    const std::string motor_esc = R"(
  "motors": [{"id": "m", "name": "test motor", "type": "bldc", "ke_v_s_per_rad": 0.01,
              "kt_nm_per_a": 0.016431676725154984, "rm_ohm": 0.1, "io_a": 0.5, "source": {"dataset": "test"}}],
  "escs": [{"id": "e", "name": "test ESC", "resc_ohm": 0.02, "c1": 1.1095279993106997, "c0": 0,
            "tr_sat": 1, "sat_slope": 1, "source": {"dataset": "test"}})";
    const std::string good_prop = R"({"id": "p", "name": "power-law prop", "diameter_m": 0.254, "thrust_law_n": 0.2,
             "thrust_law_exp": 2.0, "power_law_w": 0.42, "power_law_exp": 3.0, "law_rho_kg_m3": 1.225,
             "source": {"dataset": "test"}})";
    std::ofstream(dir_ / "cat" / "c.json")
        << "{" << motor_esc << "],\n  \"props\": [" << good_prop << "]}";
    // The unphysical entries live in a catalog of their own: Catalog::Load refuses it whole.
    fs::create_directories(dir_ / "badcat");
    std::ofstream(dir_ / "badcat" / "c.json") << "{" << motor_esc << R"(,
           {"id": "bad", "name": "ESC that creates energy", "resc_ohm": 0.02, "c1": 0.5, "c0": 0,
            "tr_sat": 1, "sat_slope": 1, "source": {"dataset": "test"}}],
  "props": [)" << good_prop << R"(,
            {"id": "hot", "name": "too good", "diameter_m": 0.254, "thrust_law_n": 2.0,
             "thrust_law_exp": 2.0, "power_law_w": 1.5, "power_law_exp": 3.0, "law_rho_kg_m3": 1.225,
             "source": {"dataset": "test"}}]})";
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string Sim(const std::string& args) const {
    return "simulate --catalog " + (dir_ / "cat").string() + " --motor m --esc e " + args;
  }
  fs::path dir_;
};

TEST_F(StandCli, PropAtRpmJsonMatchesHandComputation) {
  const CliRun r = RunCli(Sim("--prop p --vdc 12 --rpm 4000 --json"));
  ASSERT_EQ(r.code, 0) << r.err;
  const Json j = ParseJsonText(r.out, "stdout");
  // Hand computation: T = 0.2*4^2, P = 0.42*4^3, Q = P/omega; Irms = Io + Q/KT (42), VLL = Rm*I +
  // KE*omega, TR = (VLL + RESC*I)/(0.6752*VDC) (47, 48), IDC = 1.1095*TR*I (57).
  const double omega = 4000.0 * kPi / 30.0, power = 0.42 * 64.0, q = power / omega;
  const double i = 0.5 + q / 0.016431676725154984;
  const double tr = (0.1 * i + 0.01 * omega + 0.02 * i) / (kVllRmsPerVdc * 12.0);
  const double idc = kIdealIdcPerIrmsPerThrottle * tr * i;
  EXPECT_NEAR(j["thrust_n"].get<double>(), 3.2, 1e-9);
  EXPECT_NEAR(j["torque_nm"].get<double>(), q, 1e-12);
  EXPECT_NEAR(j["throttle"].get<double>(), tr, 1e-9);
  EXPECT_NEAR(j["idc_a"].get<double>(), idc, 1e-9 * idc);
  EXPECT_NEAR(j["pmech_w"].get<double>(), power, 1e-9);
  EXPECT_NEAR(j["g_per_w"].get<double>(), 3.2 / kNewtonPerGramForce / (12.0 * idc), 1e-6);
  // FM = T^1.5/(P*sqrt(2*rho*A)), A = pi*D^2/4 (momentum theory, docs/model.md section 10).
  const double area = kPi * 0.254 * 0.254 / 4.0;
  EXPECT_NEAR(j["figure_of_merit"].get<double>(), std::pow(3.2, 1.5) / (power * std::sqrt(2 * 1.225 * area)), 1e-9);
  EXPECT_EQ(j["prop"], "p");
  EXPECT_TRUE(j["prop_in_data"].get<bool>());
  EXPECT_TRUE(j["feasible"].get<bool>());
}

TEST_F(StandCli, PropForwardAndThrustAndTable) {
  // Forward at TR 0.7: the positive root of (k*R/KT)*w^2 + KE*w + R*Io - 0.6752*VDC*TR = 0.
  const CliRun f = RunCli(Sim("--prop p --vdc 12 --throttle 0.7 --json"));
  ASSERT_EQ(f.code, 0) << f.err;
  const Json jf = ParseJsonText(f.out, "stdout");
  const double k = 0.42 * std::pow(30.0 / (kPi * 1000.0), 3.0), rt = 0.12, kt = 0.016431676725154984;
  const double a = k * rt / kt, c = rt * 0.5 - kVllRmsPerVdc * 12.0 * 0.7;
  const double w = (-0.01 + std::sqrt(1e-4 - 4 * a * c)) / (2 * a);
  EXPECT_NEAR(jf["omega_rad_s"].get<double>(), w, 1e-8 * w);
  EXPECT_TRUE(jf["converged"].get<bool>());
  // Asking for that thrust gives the same speed back.
  const double thrust = jf["thrust_n"].get<double>();
  const CliRun t = RunCli(Sim("--prop p --vdc 12 --thrust-n " + std::to_string(thrust) + " --json"));
  ASSERT_EQ(t.code, 0) << t.err;
  EXPECT_NEAR(ParseJsonText(t.out, "stdout")["omega_rad_s"].get<double>(), w, 1e-5 * w);
  // Without a load: the table over throttle, 10 rows, text and JSON.
  const CliRun tab = RunCli(Sim("--prop p --vdc 12"));
  ASSERT_EQ(tab.code, 0) << tab.err;
  EXPECT_NE(tab.out.find("TR %     rpm  thrust N  thrust gf    IDC A    PDC W  Pmech W    g/W  eta_sys %     FM"),
            std::string::npos) << tab.out;
  EXPECT_EQ(Lines(tab.out), 12);
  const CliRun tj = RunCli(Sim("--prop p --vdc 12 --json"));
  ASSERT_EQ(tj.code, 0) << tj.err;
  const Json jt = ParseJsonText(tj.out, "stdout");
  ASSERT_EQ(jt["throttles"].size(), 10u);
  EXPECT_NEAR(jt["throttles"][6]["omega_rad_s"].get<double>(), w, 1e-8 * w);  // TR 70 %
  if (std::system("command -v gnuplot > /dev/null 2>&1") == 0) {
    const CliRun pl = RunCli(Sim("--prop p --vdc 12 --plot " + (dir_ / "fig").string()));
    ASSERT_EQ(pl.code, 0) << pl.err;
    EXPECT_GT(fs::file_size(dir_ / "fig" / "thrust_current_vs_throttle.png"), 1000u);
    EXPECT_NE(pl.err.find("wrote "), std::string::npos) << pl.err;
  }
}

// Propeller data that beat momentum theory (FM > 1) never reach a result: the catalog reader
// refuses them (docs/model.md section 10), naming the file, the entry and the rule.
TEST_F(StandCli, FigureOfMeritAboveOneIsRefusedAtLoad) {
  const CliRun j = RunCli("simulate --catalog " + (dir_ / "badcat").string() +
                          " --motor m --esc e --prop hot --vdc 12 --rpm 3000 --json");
  EXPECT_EQ(j.code, 65) << j.err;
  EXPECT_TRUE(j.out.empty()) << j.out;
  EXPECT_NE(j.err.find("id=hot"), std::string::npos) << j.err;
  EXPECT_NE(j.err.find("beats momentum theory"), std::string::npos) << j.err;
}

TEST_F(StandCli, PropBadInputIsOneLine) {
  struct Case {
    std::string args;
    int code;
    std::string message;
  };
  const std::vector<Case> cases = {
      {Sim("--prop nope --vdc 12 --throttle 0.5"), 64, "unknown propeller id 'nope'"},
      {Sim("--vdc 12 --thrust-n 5"), 64, "--thrust-n needs --prop"},
      {Sim("--prop p --vdc 12 --throttle 0.5 --torque 0.1"), 64, "--prop is the load"},
      {Sim("--prop p --vdc 12 --throttle 0.5 --rpm 3000"), 64, "exactly one of throttle"},
      {Sim("--prop p --vdc 12 --thrust-n -2"), 64, "thrust_n = -2: must be > 0 N"},
      {Sim("--prop p --throttle 0.5"), 64, "--vdc is required"},
  };
  for (const auto& c : cases) {
    const CliRun r = RunCli(c.args);
    EXPECT_EQ(r.code, c.code) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find("dynosize: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << "\n" << r.err;
    EXPECT_EQ(Lines(r.err), 1) << c.args << "\n" << r.err;
    EXPECT_TRUE(r.out.empty()) << c.args;
  }
}

TEST_F(StandCli, BatchRowsNamePropellers) {
  std::ofstream(dir_ / "points.csv") << "vdc_v,throttle,torque_nm,rpm,prop,thrust_n\n"
                                        "12,0.5,0.05,,,\n12,,,4000,p,\n12,,,,p,10\n";
  const CliRun r = RunCli(Sim("--batch " + (dir_ / "points.csv").string()));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(Lines(r.out), 4);
  EXPECT_NE(r.out.find(",limits,prop,thrust_n,g_per_w\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(",p,3.2,"), std::string::npos) << r.out;  // thrust at 4000 rpm
  // The thrust row: the propeller's thrust at the speed solved to 1e-10 (printed to 10 digits).
  const auto at = r.out.rfind(",p,");
  ASSERT_NE(at, std::string::npos) << r.out;
  EXPECT_NEAR(std::stod(r.out.substr(at + 3)), 10.0, 1e-8) << r.out;
  std::ofstream(dir_ / "bad.csv") << "vdc_v,rpm,prop\n12,4000,nope\n";
  const CliRun b = RunCli(Sim("--batch " + (dir_ / "bad.csv").string()));
  EXPECT_EQ(b.code, 65) << b.err;
  EXPECT_NE(b.err.find("bad.csv:2: unknown propeller id 'nope'"), std::string::npos) << b.err;
  EXPECT_EQ(Lines(b.err), 1) << b.err;
}

// An ESC with c1 + c0 < 1.1095 creates energy (docs/model.md section 10): the catalog refuses it at
// load (exit 65 naming the rule), so simulate never reports such a point. (Points that create
// energy through parameters given in code are flagged creates_energy by the model:
// tests/model/physics_test.cc.)
TEST_F(StandCli, SimulateNeverCallsAnEnergyCreatingPointFeasible) {
  const std::string base = "simulate --catalog " + (dir_ / "badcat").string() + " --motor m --esc bad --vdc 12 ";
  for (const std::string args : {"--throttle 0.6 --torque 0.05 --json", "--prop p --throttle 0.6", ""}) {
    const CliRun j = RunCli(base + args);
    EXPECT_EQ(j.code, 65) << j.err;
    EXPECT_TRUE(j.out.empty()) << j.out;
    EXPECT_NE(j.err.find("id=bad"), std::string::npos) << j.err;
    EXPECT_NE(j.err.find("1.1095"), std::string::npos) << j.err;
  }
}

TEST_F(StandCli, ValidateStandBadInput) {
  std::ofstream(dir_ / "no_speed.csv") << "time_s,vdc_v,idc_a,torque_nm\n0,12,1,0.01\n1,12,2,0.02\n";
  std::ofstream(dir_ / "no_load.csv") << "vdc_v,rpm,idc_a\n12,3000,1\n12,4000,2\n";
  const std::string cat = "validate-stand --catalog " + (dir_ / "cat").string() + " --motor m --esc e ";
  struct Case {
    std::string args;
    int code;
    std::string message;
  };
  const std::string mapped = " --format mapped --map vdc_v=vdc_v --map rpm=rpm --map idc_a=idc_a";
  const std::vector<Case> cases = {
      {cat + (dir_ / "no_speed.csv").string() + " --format mapped --map vdc_v=vdc_v --map idc_a=idc_a "
             "--map torque_nm=torque_nm", 65, "neither an rpm nor a throttle column"},
      {cat + (dir_ / "no_load.csv").string() + mapped, 65, "no torque column and no --prop"},
      {cat + (dir_ / "no_load.csv").string() + mapped + " --prop nope", 64, "unknown propeller id 'nope'"},
      {cat + (dir_ / "missing.csv").string(), 66, "missing.csv"},
      {cat + (dir_ / "no_load.csv").string() + mapped + " --prop p --lines 5-2", 64, "--lines '5-2'"},
  };
  for (const auto& c : cases) {
    const CliRun r = RunCli(c.args);
    EXPECT_EQ(r.code, c.code) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << "\n" << r.err;
    EXPECT_EQ(Lines(r.err), 1) << c.args << "\n" << r.err;
    EXPECT_TRUE(r.out.empty()) << c.args;
  }
  // With the propeller the same table predicts (no torque needed).
  const CliRun ok = RunCli(cat + (dir_ / "no_load.csv").string() + mapped + " --prop p --json");
  ASSERT_EQ(ok.code, 0) << ok.err;
  EXPECT_EQ(ParseJsonText(ok.out, "stdout")["rows_used"].get<int>(), 2);
}

// One propeller's block of a table that holds several (sjkim's AT3520 table): --where or --lines.
TEST_F(StandCli, ValidateStandSelectsRowsByColumnOrLines) {
  std::ofstream(dir_ / "two.csv") << "prop,vdc_v,rpm,idc_a\nA,12,3000,1\nA,12,4000,2\nB,12,3000,1.5\n"
                                     "B,12,4000,2.5\nB,12,5000,4\n";
  const std::string base = "validate-stand --catalog " + (dir_ / "cat").string() + " --motor m --esc e --prop p " +
                           (dir_ / "two.csv").string() +
                           " --format mapped --map vdc_v=vdc_v --map rpm=rpm --map idc_a=idc_a --json";
  const CliRun w = RunCli(base + " --where prop=B");
  ASSERT_EQ(w.code, 0) << w.err;
  const Json jw = ParseJsonText(w.out, "stdout");
  EXPECT_EQ(jw["rows_used"].get<int>(), 3);
  EXPECT_EQ(jw["rows"][0]["line"].get<int>(), 4);
  const CliRun l = RunCli(base + " --lines 2-3");
  ASSERT_EQ(l.code, 0) << l.err;
  const Json jl = ParseJsonText(l.out, "stdout");
  EXPECT_EQ(jl["rows_used"].get<int>(), 2);
  EXPECT_EQ(jl["dropped"]["outside the line range"].get<int>(), 3);
}

// A real table: T-Motor AT4125 with APC 15x8 (sjkim), the catalog's APC 15x8E (PER3).
TEST(StandCliReal, At4125WithApc15x8) {
  const std::string table = std::string(DYNOSIZE_SHARED_DIR) + "/data/sjkim_mfr_motor_tables/TMotor_AT4125_540kv.csv";
  if (!fs::exists(table)) GTEST_SKIP() << "needs ../shared/data (" << table << ")";
  const CliRun r = RunCli("validate-stand " + table + " --motor sj_m_tmotor_at4125_540kv --esc dc_e_154 "
                          "--prop apc_per3_15x8e --format mapped --map throttle=throttle --map vdc_v=voltage_V "
                          "--map idc_a=current_A --map rpm=rpm --map torque_nm=torque_Nm "
                          "--map \"thrust_n=thrust_g [g]\" --json");
  if (r.code == 64 && r.err.find("unknown") != std::string::npos) {
    GTEST_SKIP() << "catalog ids changed (merged or excluded entries): update this test: " << r.err;
  }
  ASSERT_EQ(r.code, 0) << r.err;
  const Json j = ParseJsonText(r.out, "stdout");
  EXPECT_EQ(j["rows_used"].get<int>(), 12);
  const Json& at = j["errors"]["at_measured_rpm"];
  EXPECT_EQ(at["dynosize"]["thrust_n"]["n"].get<int>(), 12);
  // Thrust at the measured rpm is the propeller entry alone: APC's PER3 table against T-Motor's
  // measurement, 5.8 % low when written; the issue's goal is <= 8 %.
  EXPECT_LT(at["dynosize"]["thrust_n"]["mae"].get<double>(), 8.0);
  EXPECT_DOUBLE_EQ(at["dynosize"]["thrust_n"]["mae"].get<double>(), at["plain_dc"]["thrust_n"]["mae"].get<double>());
  // The baseline's current in row 1 from its own definition and the propeller torque it used.
  const Json& row = j["rows"][0];
  const Json& b = j["baseline"];
  const double q = row["at_measured_rpm"]["plain_dc"]["torque_nm"].get<double>();
  const double i = b["io_a"].get<double>() + q / b["kt_nm_per_a"].get<double>();
  const double u = row["measured"]["rpm"].get<double>() / b["kv_rpm_per_v"].get<double>() + b["r_ohm"].get<double>() * i;
  EXPECT_NEAR(row["at_measured_rpm"]["plain_dc"]["idc_a"].get<double>(), u * i / row["vdc_v"].get<double>(), 1e-9);
  EXPECT_NEAR(b["kt_nm_per_a"].get<double>(), 60.0 / (2 * kPi * b["kv_rpm_per_v"].get<double>()), 1e-15);
  // The default baseline is what a DC calculator is given: the table fit's R_dc (rm_dc_ohm
  // 0.081 ohm in the catalog when written) plus the ESC's 1 mOhm in DC terms, Io_dc = 1.1095*io_a.
  EXPECT_EQ(b["numbers"].get<std::string>(), "datasheet");
  EXPECT_NEAR(b["r_ohm"].get<double>(), 0.081 + 0.001 / 0.7492, 2e-3 * b["r_ohm"].get<double>());
  // At the measured rpm and torque the two models are then one model up to the ESC prior
  // (C1 1.10953 against 1.1095280, rm_ohm rounded to 3 digits): the same current within 0.1 %.
  const Json& both = j["errors"]["at_measured_rpm_and_torque"];
  EXPECT_NEAR(both["dynosize"]["idc_a"]["mae"].get<double>(), both["plain_dc"]["idc_a"]["mae"].get<double>(), 0.1);
  // Every mode that applies is there, for both models.
  for (const char* mode : {"at_measured_rpm", "at_measured_rpm_and_torque", "from_throttle"}) {
    EXPECT_TRUE(j["errors"][mode]["dynosize"].contains("idc_a")) << mode;
    EXPECT_TRUE(j["errors"][mode]["plain_dc"].contains("idc_a")) << mode;
  }
}

// --ideal-esc (the table's ESC unknown, its drop already in the motor's fitted R): both models
// get eq (56)'s ESC, so forward from the throttle they agree too, also on the 100 % row that the
// catalog prior's knee (tr_sat 0.9) slows down; --baseline as-stored feeds the rms numbers.
TEST(StandCliReal, At4125IdealEscAndBaselineChoice) {
  const std::string table = std::string(DYNOSIZE_SHARED_DIR) + "/data/sjkim_mfr_motor_tables/TMotor_AT4125_540kv.csv";
  if (!fs::exists(table)) GTEST_SKIP() << "needs ../shared/data (" << table << ")";
  const std::string base = "validate-stand " + table + " --motor sj_m_tmotor_at4125_540kv --esc dc_e_154 "
                           "--format mapped --map throttle=throttle --map vdc_v=voltage_V --map idc_a=current_A "
                           "--map rpm=rpm --map torque_nm=torque_Nm --json";
  const CliRun prior = RunCli(base);
  const CliRun ideal = RunCli(base + " --ideal-esc");
  const CliRun stored = RunCli(base + " --baseline as-stored");
  if (prior.code == 64 && prior.err.find("unknown") != std::string::npos) {
    GTEST_SKIP() << "catalog ids changed (merged or excluded entries): update this test: " << prior.err;
  }
  ASSERT_EQ(prior.code, 0) << prior.err;
  ASSERT_EQ(ideal.code, 0) << ideal.err;
  ASSERT_EQ(stored.code, 0) << stored.err;
  const Json jp = ParseJsonText(prior.out, "prior"), ji = ParseJsonText(ideal.out, "ideal");
  const Json js = ParseJsonText(stored.out, "stored");
  EXPECT_TRUE(ji["ideal_esc"].get<bool>());
  const Json& last_p = jp["rows"].back()["from_throttle"];
  const Json& last_i = ji["rows"].back()["from_throttle"];
  ASSERT_EQ(jp["rows"].back()["measured"]["throttle"].get<double>(), 1.0);
  // Ideal ESC: dynosize = DC model up to the rounding of rm_ohm (3 digits: 0.0607 against
  // 0.7492 x 0.081 = 0.06069, 0.02 % of R; the R*I drop is a third of VDC): 2e-4 relative.
  EXPECT_NEAR(last_i["dynosize"]["rpm"].get<double>(), last_i["plain_dc"]["rpm"].get<double>(),
              2e-4 * last_i["plain_dc"]["rpm"].get<double>());
  // The prior's knee: at least 3 % slower at full throttle than the DC model (96.1 % of the voltage).
  EXPECT_LT(last_p["dynosize"]["rpm"].get<double>(), 0.97 * last_p["plain_dc"]["rpm"].get<double>());
  // as-stored: R = rm_ohm + resc_ohm, the rms numbers.
  EXPECT_EQ(js["baseline"]["numbers"].get<std::string>(), "as-stored");
  EXPECT_NEAR(js["baseline"]["r_ohm"].get<double>(), 0.0607 + 0.001, 1e-3);
}

}  // namespace
}  // namespace dynosize
