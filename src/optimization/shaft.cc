#include "optimization/shaft.h"

#include <algorithm>
#include <cmath>

#include "solvers/solver.h"

namespace dynosize {

ShaftSolution SolveShaftSpeed(const Drive& drive, const ShaftRequest& req,
                              const std::string& algorithm) {
  ShaftSolution s;
  s.algorithm = algorithm;
  auto torque_at = [&](double w) { return req.power_w ? *req.power_w / w : *req.torque_nm; };
  if (!req.omega_rad_s.free()) {
    s.omega_rad_s = req.omega_rad_s.lo;
    s.point = drive.Inverse(req.vdc_v, torque_at(s.omega_rad_s), s.omega_rad_s);
    s.solved = true;
    s.algorithm = "fixed";
    s.message = "speed fixed by the mission";
    return s;
  }
  // Variable: omega scaled by the upper bound, so that x is O(1) for the solver.
  const double w_scale = req.omega_rad_s.hi;
  const double vdc = req.vdc_v;
  const std::optional<double> power = req.power_w, torque = req.torque_nm;
  const double t_max = req.max_throttle, i_max = req.max_current_a;
  auto pieces = [&drive, vdc, power, torque, w_scale](const auto* x) {
    using T = std::decay_t<decltype(x[0])>;
    const T w = x[0] * w_scale;
    const T q = power ? T(*power) / w : T(*torque);
    return std::make_pair(ShaftPdc<T>(drive, vdc, w, q), q * w);
  };
  Problem p;
  p.name = "shaft speed";
  p.num_variables = 1;
  p.lower_bounds = Eigen::VectorXd::Constant(1, req.omega_rad_s.lo / w_scale);
  p.upper_bounds = Eigen::VectorXd::Constant(1, 1.0);
  p.initial_point = Eigen::VectorXd::Constant(1, 0.5 * (req.omega_rad_s.lo / w_scale + 1.0));
  p.variable_names = {"omega/omega_max"};
  // Maximise eta_system = Pmech/PDC: minimise its negative (dimensionless, O(1)).
  p.objective = AutoDiffObjective<1>(
      [pieces](const auto* x) {
        const auto [e, pm] = pieces(x);
        return -(pm / e.pdc_w);
      },
      1);
  p.num_inequality_constraints = 3;
  p.inequality_names = {"throttle <= max", "Irms <= limit", "IDC <= limit"};
  p.inequality_constraints = AutoDiffConstraints<1>(
      [pieces, t_max, i_max](const auto* x, auto* g) {
        const auto e = pieces(x).first;
        g[0] = e.throttle - t_max;
        g[1] = (e.current_a - i_max) / i_max;
        g[2] = (e.idc_a - i_max) / i_max;
      },
      1, 3);
  SolverOptions o;
  o.algorithm = algorithm;
  o.relative_tolerance = 1e-10;
  o.max_solver_time_in_seconds = 5.0;
  const SolverResult r = Solve(p, o);
  s.solved = r.is_success();
  s.message = r.BriefReport();
  const double x = r.x.size() == 1 && std::isfinite(r.x[0]) ? r.x[0] : p.initial_point[0];
  s.omega_rad_s = std::clamp(x, p.lower_bounds[0], 1.0) * w_scale;
  s.point = drive.Inverse(vdc, torque_at(s.omega_rad_s), s.omega_rad_s);
  return s;
}

}  // namespace dynosize
