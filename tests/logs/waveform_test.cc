// The two-wattmeter analyser on synthetic trapezoid/rectangle waveforms with PWM chatter and
// noise (no public capture exists). Model: model.md section 4, eqs 28-41.
//
// Ideal waveforms (phase-voltage trapezoid of peak Vpk: 120 deg flat, 60 deg ramps; phase
// current rectangle of peak Ipk conducting during the flat 120 deg):
//   line voltage vAB: trapezoid of peak 2*Vpk, mean square (1/3)*4 + (2/3)*(4/3) = 20/9 Vpk^2
//   => VLL,rms = sqrt(20/9)*Vpk;   Irms = sqrt(2/3)*Ipk;   PAC = 2*Vpk*Ipk
//   => PAC = sqrt(27/10)*VLL,rms*Irms (eq 41), since sqrt(27/10*20/9*2/3) = 2.
#include "logs/waveform.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <sstream>

#include "common/error.h"
#include "common/units.h"
#include "logs/log_test_util.h"

namespace dynosize::logs {
namespace {

using testing_util::RelErr;
using testing_util::WriteTemp;

// Unit trapezoid of the phase back-EMF; theta in degrees, rising zero crossing at 0.
double Trapezoid(double theta_deg) {
  double t = std::fmod(theta_deg + 30.0, 360.0);
  if (t < 0) t += 360.0;  // t = 0 at the start of the rising ramp
  if (t < 60.0) return -1.0 + t / 30.0;
  if (t < 180.0) return 1.0;
  if (t < 240.0) return 1.0 - (t - 180.0) / 30.0;
  return -1.0;
}
// Unit rectangle: +1 on the positive flat, -1 on the negative flat, 0 on the ramps.
double Rectangle(double theta_deg) {
  double t = std::fmod(theta_deg + 30.0, 360.0);
  if (t < 0) t += 360.0;
  if (t >= 60.0 && t < 180.0) return 1.0;
  if (t >= 240.0) return -1.0;
  return 0.0;
}

struct Synth {
  std::vector<double> van, vbn, vcn, ia, ib;
  double fs = 250e3;  // the paper's DAQ rate (model.md section 1)
};

// Noise model (seeded): PWM chatter = 20 kHz square wave of chatter_frac*Vpk on each phase
// while it is on a flat part (independent phase per leg), current ripple = 20 kHz triangle of
// ripple_frac*Ipk, white Gaussian noise of noise_frac of the peak on every channel, and a
// common-mode voltage (Vdc/2 plus a 20 kHz square) that the line-line differences cancel.
Synth Make(double vpk, double ipk, double fe, double periods, double start_deg, double chatter_frac,
           double ripple_frac, double noise_frac, unsigned seed) {
  Synth s;
  const std::size_t n = static_cast<std::size_t>(periods * s.fs / fe);
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  const double fpwm = 20e3;
  for (std::size_t k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) / s.fs;
    const double th = start_deg + 360.0 * fe * t;
    auto sq = [&](double phase) { return std::fmod(fpwm * t + phase, 1.0) < 0.5 ? 1.0 : -1.0; };
    auto tri = [&](double phase) {
      const double x = std::fmod(fpwm * t + phase, 1.0);
      return x < 0.5 ? 4.0 * x - 1.0 : 3.0 - 4.0 * x;
    };
    const double common = 8.0 + 0.5 * sq(0.37);
    double v[3], i[3];
    for (int p = 0; p < 3; ++p) {
      const double thp = th - 120.0 * p;
      const bool flat = Rectangle(thp) != 0.0;
      v[p] = vpk * Trapezoid(thp) + common + (flat ? chatter_frac * vpk * sq(0.21 * p) : 0.0) +
             noise_frac * vpk * noise(rng);
      i[p] = ipk * Rectangle(thp) + ripple_frac * ipk * tri(0.13 * p) + noise_frac * ipk * noise(rng);
    }
    s.van.push_back(v[0]);
    s.vbn.push_back(v[1]);
    s.vcn.push_back(v[2]);
    s.ia.push_back(i[0]);
    s.ib.push_back(i[1]);
  }
  return s;
}

AcQuantities Analyze(const Synth& s) {
  return AnalyzeThreePhase(s.van.data(), s.vbn.data(), s.vcn.data(), s.ia.data(), s.ib.data(),
                           s.van.size(), s.fs);
}

// Ideal waveforms at 625 samples per period: the current rectangles are discontinuous, and
// each of their 4 edges per period is resolved only to one sample; the trapezoid rule then errs
// by up to half a sample of Ipk^2 per edge, which mostly cancels between rising and falling
// edges: 2e-4 observed, 1e-3 allowed. iC = -(iA + iB) has twice as many edge samples.
constexpr double kIdealRelTol = 1e-3;
constexpr double kIdealDerivedCurrentRelTol = 5e-3;
// With chatter (2 %), ripple (2 %) and noise (0.5 %): these add in quadrature to the rms values
// (about +1.3e-4 relative on VLL) and average out of PAC; 2e-3 leaves a 10x margin.
constexpr double kNoisyRelTol = 2e-3;
// The acceptance test: PAC within 1 % of sqrt(27/10)*VLL,rms*Irms (eq 41).
constexpr double kExchangeRateTol = 0.01;

TEST(Waveform, IdealTrapezoidMatchesClosedForms) {
  const double vpk = 6.0, ipk = 10.0;
  const Synth s = Make(vpk, ipk, 400.0, 12.3, 17.0, 0.0, 0.0, 0.0, 1);
  const AcQuantities q = Analyze(s);
  EXPECT_EQ(q.periods, 11u);  // 12.3 periods starting at 17 deg: 11 whole rising-to-rising
  EXPECT_LT(RelErr(q.electrical_frequency_hz, 400.0), kIdealRelTol);
  EXPECT_LT(RelErr(q.vll_rms_v, std::sqrt(20.0 / 9.0) * vpk), kIdealRelTol);
  EXPECT_LT(RelErr(q.irms_a, std::sqrt(2.0 / 3.0) * ipk), kIdealRelTol);
  EXPECT_LT(RelErr(q.pac_w, 2.0 * vpk * ipk), kIdealRelTol);
  EXPECT_LT(std::fabs(q.exchange_rate_ratio - 1.0), kIdealRelTol);
  EXPECT_LT(RelErr(q.i_c_rms_a, q.i_a_rms_a), kIdealDerivedCurrentRelTol);
}

TEST(Waveform, ChatterAndNoiseStillGiveEq41WithinOnePercent) {
  const double vpk = 5.3, ipk = 7.5;
  for (unsigned seed : {11u, 12u, 13u}) {
    const Synth s = Make(vpk, ipk, 733.0, 9.7, 211.0, 0.02, 0.02, 0.005, seed);
    const AcQuantities q = Analyze(s);
    SCOPED_TRACE(seed);
    EXPECT_LT(RelErr(q.vll_rms_v, std::sqrt(20.0 / 9.0) * vpk), kNoisyRelTol);
    EXPECT_LT(RelErr(q.irms_a, std::sqrt(2.0 / 3.0) * ipk), kNoisyRelTol);
    EXPECT_LT(RelErr(q.pac_w, 2.0 * vpk * ipk), kNoisyRelTol);
    EXPECT_LT(std::fabs(q.pac_w / (kPacPerVllIrms * q.vll_rms_v * q.irms_a) - 1.0), kExchangeRateTol);
    EXPECT_LT(RelErr(q.electrical_frequency_hz, 733.0), kNoisyRelTol);
    std::cout << "[waveform] seed " << seed << ": VLL rel err "
              << RelErr(q.vll_rms_v, std::sqrt(20.0 / 9.0) * vpk) << ", Irms rel err "
              << RelErr(q.irms_a, std::sqrt(2.0 / 3.0) * ipk) << ", PAC rel err "
              << RelErr(q.pac_w, 2.0 * vpk * ipk) << ", PAC/(sqrt(27/10) VLL Irms) - 1 = "
              << q.exchange_rate_ratio - 1.0 << "\n";
  }
}

TEST(Waveform, PartialPeriodsWouldBiasTheAverage) {
  // Why whole periods: the ideal two-wattmeter power is constant (2*Vpk*Ipk at every instant),
  // but the line voltage's mean square is not. Over all samples of a 12.25-period capture it
  // is off by far more than over the whole periods.
  const double vpk = 6.0, ipk = 10.0;
  const Synth s = Make(vpk, ipk, 400.0, 12.25, 100.0, 0.0, 0.0, 0.0, 1);
  double ms = 0.0;
  for (std::size_t k = 0; k < s.van.size(); ++k) ms += (s.van[k] - s.vbn[k]) * (s.van[k] - s.vbn[k]);
  const double vab_all = std::sqrt(ms / static_cast<double>(s.van.size()));
  const AcQuantities q = Analyze(s);
  const double want = std::sqrt(20.0 / 9.0) * vpk;
  EXPECT_LT(RelErr(q.v_ab_rms_v, want), kIdealRelTol);
  EXPECT_GT(RelErr(vab_all, want), 3 * kIdealRelTol);
}

TEST(Waveform, ErrorsAndCsvReader) {
  const Synth s = Make(6.0, 10.0, 400.0, 0.8, 0.0, 0.0, 0.0, 0.0, 1);
  try {
    Analyze(s);
    FAIL() << "no error";
  } catch (const DataError& e) {
    EXPECT_NE(std::string(e.what()).find("whole electrical period(s) of vAB"), std::string::npos) << e.what();
  }
  EXPECT_THROW(AnalyzeThreePhase(nullptr, s.vbn.data(), s.vcn.data(), s.ia.data(), s.ib.data(),
                                 s.van.size(), s.fs),
               UsageError);
  // A CSV capture with a time column (sample rate from it).
  const Synth c = Make(6.0, 10.0, 2000.0, 3.5, 40.0, 0.0, 0.0, 0.0, 1);
  std::ostringstream csv;
  csv.precision(17);
  csv << "time_s,v_an_v,v_bn_v,v_cn_v,i_a_a,i_b_a\r\n";
  for (std::size_t k = 0; k < c.van.size(); ++k) {
    csv << static_cast<double>(k) / c.fs << "," << c.van[k] << "," << c.vbn[k] << "," << c.vcn[k]
        << "," << c.ia[k] << "," << c.ib[k] << "\r\n";
  }
  const WaveformCapture cap = ReadWaveformCsv(WriteTemp("wave.csv", csv.str()));
  EXPECT_LT(RelErr(cap.sample_rate_hz, c.fs), 1e-9);
  const AcQuantities q = AnalyzeThreePhase(cap.v_an.data(), cap.v_bn.data(), cap.v_cn.data(),
                                           cap.i_a.data(), cap.i_b.data(), cap.v_an.size(),
                                           cap.sample_rate_hz);
  EXPECT_EQ(q.periods, 2u);  // 3.5 periods from 40 deg: rising crossings at 360, 720, 1080 deg
  EXPECT_LT(RelErr(q.pac_w, 120.0), kIdealRelTol);
  try {
    ReadWaveformCsv(WriteTemp("wave_bad.csv", "v_an_v,v_bn_v,v_cn_v,i_a_a,i_b_a,volts\n1,2,3,4,5,6\n"));
    FAIL() << "no error";
  } catch (const DataError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown column(s) \"volts\""), std::string::npos) << e.what();
  }
  EXPECT_THROW(ReadWaveformCsv(WriteTemp("wave_norate.csv", "v_an_v,v_bn_v,v_cn_v,i_a_a,i_b_a\n1,2,3,4,5\n")),
               UsageError);
}

}  // namespace
}  // namespace dynosize::logs
