// The point list read by `dynosize simulate --batch FILE` (UTF-8, LF, CRLF or CR line ends): a
// CSV with a header naming some of
// vdc_v, throttle, torque_nm, rpm, prop, thrust_n (any order; other columns are refused). Each row
// gives vdc_v and (empty cells are absent)
//  - without a prop: exactly two of throttle, torque_nm, rpm: throttle + torque_nm or
//    throttle + rpm for the forward model, torque_nm + rpm for the inverse;
//  - with a prop (a catalog propeller id, whose torque law is the load): exactly one of
//    throttle (forward), rpm or thrust_n (the throttle solved), and no torque_nm.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace dynosize {

struct PointRequest {
  std::size_t row = 0;  // 1-based line number in the file (the header is line 1)
  double vdc_v = 0.0;
  std::optional<double> throttle;
  std::optional<double> torque_nm;
  std::optional<double> rpm;
  std::string prop;                  // catalog propeller id; "" = none
  std::optional<double> thrust_n;    // only with a prop
};

// Upper bounds of requested values (docs/reliability.md): far
// beyond any electric drive, they keep every product the model forms (powers, squared speeds
// in the torque law) finite, so that a finite request gives finite results.
inline constexpr double kMaxRequestVdcV = 1e5;       // 100 kV
inline constexpr double kMaxRequestTorqueNm = 1e6;   // N*m
inline constexpr double kMaxRequestRpm = 1e7;        // rpm
inline constexpr double kMaxTorqueLawCoefficient = 1e6;  // |A|, |B|, |C| of the torque law, SI
inline constexpr double kMaxRequestThrustN = 1e6;    // N

// The range of each requested value (CheckPointRequest's rules, also checked column by column
// by the batch of api/simulate.h, hence both comparisons always made); false for NaN.
inline bool RequestVdcInRange(double v) { return (v > 0.0) & (v <= kMaxRequestVdcV); }
inline bool RequestThrottleInRange(double t) { return (t >= 0.0) & (t <= 1.0); }
inline bool RequestTorqueInRange(double q) { return (q >= 0.0) & (q <= kMaxRequestTorqueNm); }
inline bool RequestRpmInRange(double r) { return (r >= 0.0) & (r <= kMaxRequestRpm); }
inline bool RequestThrustInRange(double t) { return (t > 0.0) & (t <= kMaxRequestThrustN); }

// Throws NoInputError / DataError naming file:line, column, value and rule.
std::vector<PointRequest> ReadPointsCsv(const std::string& path);

// Checks one request's values (VDC > 0, 0 <= throttle <= 1, torque >= 0, rpm >= 0, the
// combination of given keys); returns "" or the violated rule. Shared by the CLI flags.
std::string CheckPointRequest(const PointRequest& r);

}  // namespace dynosize
