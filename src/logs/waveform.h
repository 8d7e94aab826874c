// AC quantities of a BLDC drive from raw three-phase waveforms, as the paper's power analyser
// computes them (model.md section 4, eqs 28-41):
//
//     vAC = vAN - vCN,  vBC = vBN - vCN,  vAB = vAN - vBN,  vCA = vCN - vAN
//     p(t) = vAC*iA + vBC*iB                       two-wattmeter method (iC = -iA - iB)
//     PAC  = (1/T) * integral of p over T
//     rms{x} = sqrt((1/T) * integral of x^2 over T)
//     VLL,rms = (VAB + VBC + VCA)/3                (33)
//     Irms    = (IA + IB)/2                        (34)
//
// with T a whole number of electrical periods: partial periods bias every average. Periods
// are found from the rising zero crossings of vAB with hysteresis (+-hysteresis_fraction of
// vAB's rms), so PWM chatter and noise on the flat parts of the waveform cannot fake a crossing;
// the crossing instant is interpolated linearly between samples.
//
// The phase voltages may be measured against any common reference (neutral, DC negative): only
// differences enter. For the ideal trapezoidal line voltage and rectangular current,
// PAC = sqrt(27/10) * VLL,rms * Irms (eq 41).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace dynosize::logs {

struct WaveformOptions {
  // Crossing hysteresis as a fraction of vAB's rms. 0.3: PWM chatter of the flat parts and noise
  // stay well inside +-0.3*rms, while the trapezoid's ramps sweep through it.
  double hysteresis_fraction = 0.3;
  // At least this many whole periods are required (else a DataError).
  std::size_t min_periods = 1;

  std::string Validate() const;
};

struct AcQuantities {
  double vll_rms_v = 0.0;     // eq 33
  double irms_a = 0.0;        // eq 34
  double pac_w = 0.0;         // two-wattmeter active power
  double v_ab_rms_v = 0.0, v_bc_rms_v = 0.0, v_ca_rms_v = 0.0;
  double i_a_rms_a = 0.0, i_b_rms_a = 0.0, i_c_rms_a = 0.0;  // i_c = -(i_a + i_b)
  double electrical_frequency_hz = 0.0;
  std::size_t periods = 0;    // whole electrical periods integrated
  double window_s = 0.0;      // their duration
  // PAC / (sqrt(27/10)*VLL,rms*Irms): 1 for ideal trapezoid/rectangle waveforms (eq 41).
  double exchange_rate_ratio = 0.0;
};

// Analyses n samples taken at sample_rate_hz. Throws UsageError for null pointers, n < 3 or a
// non-positive rate; DataError when vAB has fewer than min_periods whole periods or is flat.
AcQuantities AnalyzeThreePhase(const double* v_an, const double* v_bn, const double* v_cn,
                               const double* i_a, const double* i_b, std::size_t n,
                               double sample_rate_hz,
                               const WaveformOptions& options = WaveformOptions());

// A capture read from a CSV file.
struct WaveformCapture {
  std::vector<double> v_an, v_bn, v_cn, i_a, i_b;
  double sample_rate_hz = 0.0;
  std::string file;
};

// Reads a waveform CSV: header with the columns v_an_v, v_bn_v, v_cn_v, i_a_a, i_b_a and
// optionally time_s (any order; unknown columns are an error). The sample rate comes from
// time_s (uniform sampling checked: every interval within 1 % of the median) or, without a
// time column, from sample_rate_hz (> 0). Strict like the canonical log: every cell a finite
// number. BOM and LF/CRLF/CR line ends accepted.
WaveformCapture ReadWaveformCsv(const std::string& path, double sample_rate_hz = 0.0);

}  // namespace dynosize::logs
