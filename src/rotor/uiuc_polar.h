// The blade sections' polar dynosize uses where a propeller's airfoils are unknown (most are):
// fitted by Levenberg-Marquardt (rotor/airfoil_fit.h, eq B11) on every UIUC propeller of volumes
// 1-3 whose blade UIUC measured, static and J-sweep points; `dynosize rotor validate --constants`
// prints it again from the data, and docs/validation.md ("Propellers from their geometry") gives
// its error when each family is left out. cl_min, cl_cd0 and re_ref are held (not fitted).
#pragma once

#include "rotor/airfoil.h"

namespace dynosize {

inline constexpr AirfoilPolar kUiucFittedPolar{
    /*cl0=*/0.2584, /*cl_alpha_per_rad=*/4.869, /*cl_max=*/1.421, /*cl_min=*/-0.4,
    /*cd0=*/0.02256, /*cd2=*/0.147, /*cl_cd0=*/0.5, /*re_ref=*/7e+04, /*re_exp=*/-0.2049};

}  // namespace dynosize
