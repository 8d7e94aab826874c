// Forward-flight physics of a segment: the thrust each rotor must give and the component of
// the airspeed along its axis (the advance ratio the propeller model sees).
//
//  - hover: T_total = W (momentum balance at zero speed).
//  - climb (rate Vc, < 0 descends): T_total = W + D(Vc), D = 1/2*rho*Vc*|Vc|*Cd*A, the rotor
//    axis vertical and the axial inflow Vc. A descent is given the static propeller data
//    (axial inflow 0): the propeller tables do not cover negative advance ratios, and the
//    vortex-ring state makes momentum theory invalid there (Leishman, Principles of Helicopter
//    Aerodynamics, 2nd ed., sec. 2.13); the static value is the usual conservative stand-in.
//  - cruise without a wing (a multirotor): the standard steady-level forward-flight balance
//    of a multirotor (e.g. Bangura & Mahony, "Nonlinear dynamic modeling for high performance
//    control of a quadrotor", ACRA 2012; Leishman sec. 2.14-2.15): the thrust vector tilts
//    forward by theta so that T*cos(theta) = W and T*sin(theta) = D(V), hence
//        T_total = sqrt(W^2 + D^2),  theta = atan(D/W),
//    and the airspeed component along the rotor axis is V*sin(theta) (the propeller data are
//    axial; the edgewise component is neglected, which is conservative: edgewise flow adds
//    translational lift).
//  - cruise with a wing (lift + cruise): the wing carries W, the cruise rotors give
//        T_total = W/(L/D) + 1/2*rho*V^2*Cd*A_add
//    along the flight path, axial inflow V. A_add is the drag area the stated L/D does not
//    hold (Segment::lift_to_drag_of, mission.h): the idle groups' idle_drag_area_m2 (stopped
//    rotors) always, plus the body's drag_area_m2 when the L/D is the wing's alone. Cd is
//    vehicle.drag_coefficient, the one coefficient every area of the mission is multiplied by
//    (drag_area_m2 and idle_drag_area_m2 are reference areas, Cd*A the drag area proper), as in
//    the climb and the multirotor cruise. Steady level flight: thrust = total drag, and the
//    drag of an aircraft flying at W/(L/D) is W/(L/D) by the definition of L/D with L = W.
//  - coaxial pairs: the lower rotor works in the upper one's wake; at equal thrust the pair
//    needs kappa_int = 1.2816 times the induced power of two isolated rotors (Leishman sec.
//    2.14.2, Eq. 2.196, theoretical, fully contracted wake). With ideal P ~ T^(3/2) that is the
//    power of isolated rotors at kappa_int^(2/3) = 1.180 times the thrust, which is what the
//    isolated-propeller data are evaluated at.
#pragma once

#include <algorithm>
#include <cmath>

#include "common/units.h"
#include "mission/mission.h"

namespace dynosize {

inline constexpr double kCoaxialInducedPowerFactor = 1.2816;

struct RotorLoad {
  double thrust_total_n = 0.0;   // all rotors together
  double thrust_per_rotor_n = 0.0;  // what each rotor's propeller data are evaluated at
  double axial_airspeed_m_s = 0.0;
  double tilt_rad = 0.0;
  int rotors = 0;
};

// How long a segment lasts when flown at `airspeed_m_s` (used by cruise segments given by
// distance): its duration_s, distance/|climb rate|, or distance/airspeed.
inline double SegmentDurationS(const Segment& s, double airspeed_m_s) {
  if (s.duration_s) return *s.duration_s;
  if (s.type == SegmentType::kClimb) return *s.distance_m / std::fabs(s.climb_rate_m_s);
  return *s.distance_m / airspeed_m_s;
}

// The longest the segments other than the max_endurance stretch can last (cruise at the low end
// of its airspeed range).
inline double LongestFixedDurationS(const Mission& m) {
  double t = 0;
  for (std::size_t i = 0; i < m.segments.size(); ++i) {
    const bool stretched = m.objective.type == ObjectiveType::kMaxEndurance &&
                           static_cast<int>(i) == m.objective.segment_index;
    if (!stretched) t += SegmentDurationS(m.segments[i], m.segments[i].airspeed_m_s.lo);
  }
  return t;
}

// The group that lifts the vehicle: that of the first hover segment, else of the first climb;
// -1 when no segment is flown on the rotors' lift (a wing-borne cruise only).
inline int LiftGroup(const Mission& m) {
  for (const SegmentType t : {SegmentType::kHover, SegmentType::kClimb}) {
    for (const Segment& s : m.segments) {
      if (s.type == t) return s.group;
    }
  }
  return -1;
}

// The rotors that lift the vehicle: the most of the lift group that thrust in any of its hover
// or climb segments (all of the group's when a segment does not say); 0 without a lift group.
inline int LiftRotors(const Mission& m) {
  const int g = LiftGroup(m);
  int n = 0;
  for (const Segment& s : m.segments) {
    if (s.group == g && (s.type == SegmentType::kHover || s.type == SegmentType::kClimb)) {
      n = std::max(n, s.rotors_active > 0 ? s.rotors_active : GroupRotors(m, g));
    }
  }
  return n;
}

inline RotorLoad SegmentRotorLoad(const Mission& m, const Segment& s, double total_mass_kg,
                                  double airspeed_m_s) {
  RotorLoad r;
  const double w = total_mass_kg * kStandardGravity;
  // Idle groups (stopped lift rotors in cruise) add their drag area to the body's.
  double idle_area_m2 = 0.0;
  for (std::size_t g = 0; g < m.groups.size(); ++g) {
    if (static_cast<int>(g) != s.group) idle_area_m2 += m.groups[g].idle_drag_area_m2;
  }
  const double cda = (m.vehicle.drag_area_m2 + idle_area_m2) * m.vehicle.drag_coefficient;
  r.rotors = s.rotors_active > 0 ? s.rotors_active : GroupRotors(m, s.group);
  switch (s.type) {
    case SegmentType::kHover:
    case SegmentType::kShaft:
      r.thrust_total_n = w;
      break;
    case SegmentType::kClimb: {
      const double vc = s.climb_rate_m_s;
      r.thrust_total_n = w + 0.5 * m.rho_kg_m3 * vc * std::fabs(vc) * cda;
      r.axial_airspeed_m_s = vc > 0 ? vc : 0.0;
      break;
    }
    case SegmentType::kCruise: {
      const double v = airspeed_m_s;
      const double drag = 0.5 * m.rho_kg_m3 * v * v * cda;
      if (s.lift_to_drag > 0) {
        const double add_area_m2 = idle_area_m2 + (s.lift_to_drag_of == LiftToDragOf::kWing ? m.vehicle.drag_area_m2 : 0.0);
        r.thrust_total_n = w / s.lift_to_drag + 0.5 * m.rho_kg_m3 * v * v * add_area_m2 * m.vehicle.drag_coefficient;
        r.axial_airspeed_m_s = v;
      } else {
        r.thrust_total_n = std::hypot(w, drag);
        r.tilt_rad = std::atan2(drag, w);
        r.axial_airspeed_m_s = v * std::sin(r.tilt_rad);
      }
      break;
    }
  }
  r.thrust_per_rotor_n = r.thrust_total_n / r.rotors;
  if (m.vehicle.coaxial && s.lift_to_drag <= 0) {
    r.thrust_per_rotor_n *= std::cbrt(kCoaxialInducedPowerFactor * kCoaxialInducedPowerFactor);
  }
  return r;
}

}  // namespace dynosize
