// The closed-form model of model/drive.h over many points at once, structure of arrays: the
// inputs are contiguous arrays, the outputs one contiguous array per key of the point JSON
// (report/point_json.h), written in place (std::vector storage or numpy arrays alike). The limits
// are Limit bits per point (model/drive.h), never text: a caller names them once per distinct
// code (LimitNames) at its edge.
//
// The numbers are Drive's, bit for bit: each point runs the expressions of Drive::Inverse,
// Drive::AtTorque or Drive::AtSpeed and of Drive's Complete and Flag, in their order (eqs 42, 46,
// 47, 48, 49 with the load's law, 50, 51, 52, 53, 57, 59 of docs/model.md and section 7's knee;
// the limits of section 10 through model/physics.h), written branch-free so that the compiler
// vectorises the loops. A drive with an extension of section 9 (dead band, supply resistance,
// Io(omega), heating, droop) runs Drive's scalar path point by point into the same arrays.
//
// No I/O; no allocation but PointColumnsStorage's, once per batch.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>

#include "model/drive.h"

namespace dynosize {

// The two quantities each point gives; the third is solved.
enum class BatchMode {
  kInverse,   // torque and speed given, the throttle solved (Drive::Inverse)
  kAtTorque,  // throttle and a constant load torque (Drive::AtTorque)
  kAtSpeed,   // throttle and speed (Drive::AtSpeed)
};

// n values per array, SI. kInverse reads vdc_v, torque_nm, omega_rad_s; kAtTorque vdc_v,
// throttle, torque_nm; kAtSpeed vdc_v, throttle, omega_rad_s. The others may be null.
struct BatchInputs {
  const double* vdc_v = nullptr;
  const double* throttle = nullptr;
  const double* torque_nm = nullptr;
  const double* omega_rad_s = nullptr;
};

// The outputs, one array of n per key of OperatingPoint (and of the point JSON); every pointer
// must be set, and no array may overlap another or an input. feasible[i] is limits[i] ==
// kLimitNone.
struct PointColumns {
  double* vdc_v = nullptr;
  double* throttle = nullptr;
  double* throttle_effective = nullptr;
  double* rpm = nullptr;
  double* omega_rad_s = nullptr;
  double* torque_nm = nullptr;
  double* irms_a = nullptr;
  double* vll_rms_v = nullptr;
  double* pac_w = nullptr;
  double* idc_a = nullptr;
  double* pdc_w = nullptr;
  double* pesc_w = nullptr;
  double* pmech_w = nullptr;
  double* eta_motor = nullptr;
  double* eta_esc = nullptr;
  double* eta_system = nullptr;
  bool* saturated = nullptr;
  bool* feasible = nullptr;
  std::uint32_t* limits = nullptr;

  // The same columns from point i on.
  PointColumns From(std::size_t i) const;
  // Writes one point at index i (the scalar path's result).
  void Set(std::size_t i, const OperatingPoint& p) const;
  // Reads the point at index i back (winding_rise_k is 0: the batch does not report it).
  OperatingPoint Get(std::size_t i) const;
};

// PointColumns for n points over storage this object owns (left uninitialised until a solve
// writes it): the 16 number columns in one block, the two flag columns in another.
class PointColumnsStorage {
 public:
  explicit PointColumnsStorage(std::size_t n = 0);
  std::size_t size() const { return n_; }
  const PointColumns& columns() const { return columns_; }

 private:
  std::size_t n_ = 0;
  std::unique_ptr<double[]> values_;
  std::unique_ptr<bool[]> flags_;  // saturated, feasible
  std::unique_ptr<std::uint32_t[]> limits_;
  PointColumns columns_;
};

// Solves n points of one mode on the drive into out[0, n).
void SolveBatch(const Drive& drive, BatchMode mode, std::size_t n, const BatchInputs& in, const PointColumns& out);

}  // namespace dynosize
