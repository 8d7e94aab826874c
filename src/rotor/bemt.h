// Blade-element momentum theory for propellers and rotors in static and axial operation
// (docs/model.md section 13, eqs B1-B10): the blade of rotor/blade.h cut into elements, each
// element's section (rotor/airfoil.h) in the velocity its own wake induces, with Prandtl's tip
// loss. The element equations are written, as in QPROP's formulation (M. Drela, "QPROP
// Formulation", MIT 2006), in one unknown per element, the angle psi that places the total
// velocity on a circle between the no-induction state and the fully induced one, so that static
// operation (no axial velocity) needs no special case:
//   (B5)  U = sqrt(Ua^2 + Ut^2),  Wa = (Ua + U sin psi)/2,  Wt = (Ut + U cos psi)/2,
//         va = Wa - Ua, vt = Ut - Wt,  W = sqrt(Wa^2 + Wt^2),  alpha = beta - atan(Wa/Wt)
//   (B6)  the bound circulation of the section:  Gamma = W*c*cl/2
//   (B7)  the wake's circulation with tip loss:  Gamma = vt * (4*pi*r/B) * F * sqrt(1 + (4*lw*R/(pi*B*r))^2)
//         lw = (r/R)*Wa/Wt,  F = (2/pi)*acos(exp(-f)),  f = (B/2)*(1 - r/R)/lw
//   (B8)  dT = (rho*B/2)*W*c*(cl*Wt - cd*Wa) dr,   dQ = (rho*B/2)*W*c*(cl*Wa + cd*Wt)*r dr
// Ua is the axial airspeed V, Ut = omega*r. (B6) = (B7) is solved for psi by a bracketed root
// search starting from the no-induction angle psi0 = atan(Ua/Ut). Without drag and with
// lightly loaded elements (the sqrt term 1) B8 is the annulus momentum balance
// dT = 4*pi*rho*r*F*va*(Ua + va) dr: the model conserves momentum (tests/rotor/bemt_test.cc).
// Outputs in the UIUC coefficients of prop/prop_model.h and the helicopter figures (B9, B10):
//   (B9)  FM = T^1.5/sqrt(2*rho*A) / P static; T*(V/2 + sqrt(V^2/4 + T/(2*rho*A))) / P in axial flow
//   (B10) CT/sigma = T / (rho*A*(omega*R)^2) / sigma  (blade loading), tip Mach = sqrt((omega*R)^2 + V^2)/a
// No I/O; the elements are laid out once in the constructor and Evaluate allocates nothing.
#pragma once

#include <vector>

#include "common/atmosphere.h"
#include "rotor/airfoil.h"
#include "rotor/blade.h"

namespace dynosize {

struct BemtOptions {
  int elements = 24;           // blade elements, spaced closer toward the tip
  bool tip_loss = true;        // F of eq B7 (false: F = 1)
  double viscosity_pa_s = kAirViscosityPaS;
  double speed_of_sound_m_s = kIsaSeaLevelSpeedOfSoundMS;
};

struct BemtPoint {
  double omega_rad_s = 0.0;
  double airspeed_m_s = 0.0;
  double rho_kg_m3 = 0.0;
  double thrust_n = 0.0;
  double torque_nm = 0.0;
  double power_w = 0.0;
  double ct = 0.0;  // T/(rho*n^2*D^4), n in rev/s
  double cp = 0.0;  // P/(rho*n^3*D^5)
  double j = 0.0;   // V/(n*D)
  double figure_of_merit = 0.0;  // eq B9; 0 when T <= 0 or P <= 0
  double efficiency = 0.0;       // T*V/P in axial flow; 0 static
  double tip_mach = 0.0;
  double ct_over_sigma = 0.0;    // eq B10
  double stalled_span = 0.0;     // share of the lifting span held at cl_max / cl_min
  double mean_reynolds = 0.0;    // at r = 0.75 R
  bool mach_held = false;        // some section above kMaxMach
  int unsolved_elements = 0;     // elements where B6 = B7 had no root (the no-induction state used)
};

// One element's solution, for the tests and the report of a rotor's span.
struct BemtElement {
  double r_m = 0.0, dr_m = 0.0, chord_m = 0.0, beta_rad = 0.0;
  double psi_rad = 0.0, wa_m_s = 0.0, wt_m_s = 0.0, va_m_s = 0.0, vt_m_s = 0.0;
  double alpha_rad = 0.0, cl = 0.0, cd = 0.0, reynolds = 0.0, mach = 0.0, tip_loss_f = 1.0;
  double dthrust_n = 0.0, dtorque_nm = 0.0;  // of all blades over the element
  bool stalled = false, mach_held = false, solved = true;
};

class Bemt {
 public:
  // Throws UsageError when the geometry or the polar breaks a rule (CheckBladeGeometry,
  // CheckAirfoil) or options.elements is outside 4-400.
  Bemt(const BladeGeometry& geometry, const AirfoilPolar& polar, const BemtOptions& options = {});

  // Throws UsageError for omega <= 0, airspeed < 0 or rho <= 0 (or not finite).
  BemtPoint Evaluate(double omega_rad_s, double airspeed_m_s, double rho_kg_m3) const;
  // At advance ratio j = V/(n*D) >= 0.
  BemtPoint EvaluateAtAdvanceRatio(double omega_rad_s, double j, double rho_kg_m3) const;
  // One element (index 0 .. elements()-1) at the operating point.
  BemtElement SolveElement(int index, double omega_rad_s, double airspeed_m_s, double rho_kg_m3) const;

  // Replaces the sections' polar (the fit of rotor/airfoil_fit.h); throws UsageError when
  // CheckAirfoil fails.
  void set_polar(const AirfoilPolar& polar);

  int elements() const { return static_cast<int>(elements_.size()); }
  const BladeGeometry& geometry() const { return geometry_; }
  const AirfoilPolar& polar() const { return polar_; }
  double solidity() const { return solidity_; }
  double disk_area_m2() const;

 private:
  struct Layout {
    double x, r_m, dr_m, chord_m, beta_rad;
  };
  BladeGeometry geometry_;
  AirfoilPolar polar_;
  BemtOptions options_;
  std::vector<Layout> elements_;
  double solidity_ = 0.0;
};

}  // namespace dynosize
