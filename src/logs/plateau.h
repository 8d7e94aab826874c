// Cutting a thrust-stand time series (step tests, slow ramps, closed-loop speed steps) into
// steady plateaus, and averaging each plateau robustly.
//
// Two ways to find plateaus:
//  1. by command: the log has a throttle command that moves in steps. A new step starts when the
//     command differs from the step's first sample by more than command_step_tolerance. Inside a
//     step, samples earlier than settle_time_s after the step's first sample are the transient;
//     then leading samples are dropped while the settle signal (speed, else current) is farther
//     than settle_band (relative) from the median of the step's second half ("rpm settle").
//  2. by signal: no usable command (absent, or varying every sample as in closed-loop speed
//     control). A sample is steady when, over the window of steady_window_s centred on it, at
//     least steady_min_fraction of the settle signal's samples lie within +-steady_band
//     (relative) of the window median; consecutive steady samples form a plateau, which ends
//     where the window median leaves +-steady_band of the plateau's first window median.
//  3. by ramp bins: the command varies slowly and monotonically (ramps up and/or down: fewer
//     than ramp_max_reversal_fraction of its changes reverse direction). Such a ramp is
//     quasi-steady; consecutive samples whose command falls in the same bin of width
//     ramp_bin_width form one plateau (at least ramp_min_samples). The speed lags the command
//     by the motor's time constant (7-50 ms on the stands in shared/data), so a ramp of
//     R per second biases the throttle of a point by about R * 0.05 s: under 0.2 % of the
//     range for the ramps in shared/data (<= 25 us/s).
// Plateaus with fewer than min_samples steady samples are dropped (counted).
//
// Averaging: inside a plateau a sample is an outlier when any of the averaged columns lies more
// than outlier_mad_k robust standard deviations from the column's median, with
// sigma = 1.4826*MAD (the MAD of a normal sample); when MAD is 0 (more than half the samples
// equal, as with quantised probes) sigma = 1.2533 * mean absolute deviation instead; and sigma
// is floored at mad_floor_rel*|median| so that a nearly constant signal does not turn every
// step of one count into an outlier.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace dynosize::logs {

struct PlateauOptions {
  // A command change larger than this (throttle fraction; 0.002 = 2 us on a 1000-2000 us range)
  // starts a new step. RCbenchmark writes the command exactly, so any real step exceeds it.
  double command_step_tolerance = 0.002;
  // Samples earlier than this after the first sample of a step are the transient. Motor speed
  // time constants measured in shared/data/bhabas_sar_motor_sysid are 7-50 ms; the load cells'
  // filters and the ESC's own ramp take a few hundred ms, hence 0.5 s.
  double settle_time_s = 0.5;
  // Without a time column the transient is this many samples.
  std::size_t settle_samples_without_time = 10;
  // "rpm settle": leading samples farther than this (relative) from the median of the step's
  // second half are dropped too. 3 % is about three times the speed noise of the stands in
  // shared/data at mid throttle.
  double settle_band = 0.03;
  // Plateaus with fewer steady samples are dropped.
  std::size_t min_samples = 3;
  // Outlier test inside a plateau: |x - median| > outlier_mad_k * max(1.4826*MAD,
  // mad_floor_rel*|median|). 5 sigma rejects the electrical-speed spikes and optical dropouts
  // of the real logs while keeping every sample of Gaussian noise (p ~ 6e-7 per sample).
  double outlier_mad_k = 5.0;
  double mad_floor_rel = 1e-3;
  // Ramp mode: bin width (throttle fraction; 0.02 = 20 us on a 1000-2000 us range), the
  // fewest samples per bin (1: the slow "polar" scripts log one averaged row per ~12 us), and
  // the largest fraction of command changes that reverse direction for a ramp (a PID-driven
  // command reverses about every other sample).
  double ramp_bin_width = 0.02;
  std::size_t ramp_min_samples = 1;
  double ramp_max_reversal_fraction = 0.1;
  // Signal mode: a sample is steady when at least steady_min_fraction of the samples in the
  // window of steady_window_s centred on it lie within +-steady_band of the window median
  // (the fraction, not all, because optical probes spike and drop out).
  double steady_window_s = 1.0;
  double steady_band = 0.02;
  double steady_min_fraction = 0.8;
  // The command counts as stepped when at least this fraction of the samples lie in runs of
  // min_samples or more exactly equal values. Step scripts slew between steps (the xNova
  // step logs hold 41-54 % of their samples); ramps hold under 33 %.
  double stepped_min_fraction = 0.4;
  // Signal mode without a time column: window in samples.
  std::size_t steady_window_samples_without_time = 20;
  // A log whose median sample interval is at least this is already a list of steady points
  // (the stands' "steps" scripts write one averaged row per step, 4-5 s apart): no search.
  double summary_min_interval_s = 1.0;

  // True when valid; else false, and *error (when not null) names the field, its value and the
  // rule.
  bool IsValid(std::string* error) const;
};

struct Plateau {
  std::size_t step_begin = 0;  // first sample of the step (transient included)
  std::size_t begin = 0;       // first steady sample
  std::size_t end = 0;         // one past the last steady sample
};

enum class PlateauMethod { kWholeLog, kCommandSteps, kRampBins, kSignalSteadiness };
const char* PlateauMethodName(PlateauMethod m);

// How the command moves: kStepped / kRamp / kVarying (closed loop) / kNone (absent).
enum class CommandKind { kNone, kStepped, kRamp, kVarying };
CommandKind ClassifyCommand(const double* command, std::size_t n, const PlateauOptions& options);

struct PlateauSearch {
  PlateauMethod method = PlateauMethod::kWholeLog;
  std::vector<Plateau> plateaus;
  std::size_t transient_samples = 0;      // dropped as transients (by command)
  std::size_t unsteady_samples = 0;       // not steady (by signal)
  std::size_t short_plateaus = 0;         // steps/runs with fewer than min_samples steady samples
  std::size_t short_plateau_samples = 0;  // their samples
};

// time_s, command, signal: arrays of n samples, each may be nullptr (absent). NaN in `signal`
// means "not sampled here" (asynchronous sensor) and neither breaks nor settles a plateau;
// `time_s` and `command` must be NaN-free. With command == nullptr the search is by signal;
// with both command and signal nullptr every sample is one plateau... of the whole log.
PlateauSearch FindPlateaus(const double* time_s, const double* command, const double* signal,
                           std::size_t n, const PlateauOptions& options);

// True when the command moves in steps: at least stepped_min_fraction of the samples lie in
// runs of min_samples or more exactly equal values (stand scripts hold the command exactly
// within a step).
bool CommandIsStepped(const double* command, std::size_t n, const PlateauOptions& options);

// Marks outliers in [begin, end) over the given columns (NaN cells are ignored). mask[i-begin]
// becomes 1 for an outlier sample. Returns the number of outliers.
std::size_t MarkOutliers(const std::vector<const double*>& columns, std::size_t begin,
                         std::size_t end, const PlateauOptions& options,
                         std::vector<char>* mask);

// Median of the finite values of x[begin, end) (NaN skipped); NaN when none.
double MedianOf(const double* x, std::size_t begin, std::size_t end);

}  // namespace dynosize::logs
