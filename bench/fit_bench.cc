// How long one small calibration fit takes, to back the claim "fit all 1,290 DriveCalc motors
// in under a second" (that needs < 775 us per fit on one core).
//
// The fit: 4 parameters, 30 points, the shape of a motor's input-current curve against speed
// under a propeller load, I(omega) = io + a * omega^2 + b * omega^3 ... kept generic here as
//     y = p0 + p1 * exp(-p2 * t) + p3 * t,
// with Gaussian noise sigma = 0.01 (seed 42), started 30-50 % away from the truth.
#include <benchmark/benchmark.h>

#include <random>

#include "fit/nonlinear_least_squares.h"

namespace dynosize {
namespace {

struct Data {
  Eigen::VectorXd t, y;
};

Data MakeData() {
  std::mt19937 rng(42);
  std::normal_distribution<double> noise(0.0, 0.01);
  Data d{Eigen::VectorXd(30), Eigen::VectorXd(30)};
  for (int i = 0; i < 30; ++i) {
    d.t[i] = 0.2 * i;
    d.y[i] = 0.5 + 2.0 * std::exp(-0.8 * d.t[i]) + 0.1 * d.t[i] + noise(rng);
  }
  return d;
}

template <int kN>
LeastSquaresProblem MakeProblem(const Data& d) {
  LeastSquaresProblem p;
  p.num_parameters = 4;
  p.num_residuals = 30;
  p.residuals = AutoDiffResiduals<kN>(
      [&d](const auto* x, auto* r) {
        using std::exp;
        for (int i = 0; i < 30; ++i) r[i] = x[0] + x[1] * exp(-x[2] * d.t[i]) + x[3] * d.t[i] - d.y[i];
        return true;
      },
      4);
  return p;
}

template <int kN>
void BM_LevenbergMarquardt4Params30Points(benchmark::State& state) {
  const Data d = MakeData();
  const LeastSquaresProblem p = MakeProblem<kN>(d);
  LevenbergMarquardtOptions o;
  o.use_geodesic_acceleration = state.range(0) != 0;
  int iterations = 0;
  for (auto _ : state) {
    Eigen::VectorXd x(4);
    x << 0.3, 1.2, 0.5, 0.05;
    const LevenbergMarquardtSummary s = SolveLeastSquares(p, o, &x);
    iterations = s.num_iterations;
    benchmark::DoNotOptimize(x.data());
  }
  state.counters["lm_iterations"] = iterations;
}
BENCHMARK_TEMPLATE(BM_LevenbergMarquardt4Params30Points, 4)->Arg(1)->Arg(0)->Unit(benchmark::kMicrosecond);
BENCHMARK_TEMPLATE(BM_LevenbergMarquardt4Params30Points, Eigen::Dynamic)->Arg(1)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace dynosize

BENCHMARK_MAIN();
