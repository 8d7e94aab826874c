"""Bench of dynosize.simulate (docs/python.md, "Performance"): 10^5 points of the paper's pair
through the Python module, against

  1. the C++ batch path it calls (bench/simulate_batch_bench.cc BM_SimulateColumnsInverse:
     api::SimulateColumns into result columns allocated per call), per point; goal: Python <= 1.5x
     the C++ time;
  2. a numpy implementation of the same equations written here (the first-order model's inverse:
     model.md eqs 42, 48, section 7's throttle, 46, 47, 57, 59, 52, 50, 53 and the limits of
     model/drive.h), checked equal to dynosize's numbers; goal: numpy >= 5x dynosize's time.

    PYTHONPATH=build/python /usr/bin/python3 bench/python_simulate_bench.py [build/simulate_batch_bench]

(the C++ bench is built with -DDYNOSIZE_BUILD_BENCHMARKS=ON; without it, step 1 is skipped).
"""
import json
import subprocess
import sys
import time

import numpy as np

import dynosize

N = 100_000
REPEATS = 7
ROUNDS = 3  # Python and C++ timed in turn, the best of each kept (the machine is shared)
MOTOR, ESC = "emax_1900kv_paper", "multistar_30a_paper"
VLL_RMS_PER_VDC = 0.67523723711782957  # 3/(sqrt(2)*pi), eq 46 (common/units.h)
PAC_PER_VLL_IRMS = 1.6431676725154984  # sqrt(27/10), eq 47
RAD_S_PER_RPM = np.pi / 30.0
PHYSICS_REL_TOL = 1e-9  # model/physics.h kPhysicsRelTol


def best_of(f):
    times = []
    for _ in range(REPEATS):
        t0 = time.perf_counter()
        out = f()
        times.append(time.perf_counter() - t0)
    return min(times), out


def numpy_inverse(m, e, vdc_v, torque_nm, rpm):
    """The first-order BLDC model's inverse (torque and speed given) on arrays."""
    ke, kt, rm, io = m["ke_v_s_per_rad"], m["kt_nm_per_a"], m["rm_ohm"], m["io_a"]
    resc, c1, c0, tr_sat, slope = e["resc_ohm"], e["c1"], e["c0"], e["tr_sat"], e["sat_slope"]
    omega = rpm * RAD_S_PER_RPM
    current = torque_nm / kt + io                                    # eq 42
    u = (rm + resc) * current + ke * omega                           # eq 48
    tre = u / (VLL_RMS_PER_VDC * vdc_v)                              # eq 46
    throttle = np.where(tre <= tr_sat, tre, tr_sat + (tre - tr_sat) / slope)  # section 7, inverted
    vll = VLL_RMS_PER_VDC * vdc_v * tre - resc * current             # eq 46 less the ESC's drop
    pac = PAC_PER_VLL_IRMS * vll * current                           # eq 47
    idc = (c1 * tre + c0) * current                                  # eq 57
    pdc = vdc_v * idc                                                # eq 59
    pesc = pdc - pac                                                 # eq 52
    pmech = kt * (current - io) * omega                              # eq 50
    def ratio(a, b):
        return np.where((b > 0) & (a > 0), a / np.where(b > 0, b, 1.0), 0.0)
    out = dict(throttle=throttle, throttle_effective=tre, irms_a=current, vll_rms_v=vll, pac_w=pac, idc_a=idc,
               pdc_w=pdc, pesc_w=pesc, pmech_w=pmech, eta_motor=ratio(pmech, pac), eta_esc=ratio(pac, pdc),
               eta_system=ratio(pmech, pdc))
    i_max = np.maximum(np.abs(idc), np.abs(current))
    tol = PHYSICS_REL_TOL * (np.abs(pdc) + np.abs(pac)) + 1e-12
    bad = ((throttle > 1.0) | (throttle < 0.0) | (i_max > m.get("max_current_a", np.inf))
           | (i_max > e.get("max_current_a", np.inf)) | (pac > m.get("max_power_w", np.inf))
           | (vdc_v > e.get("vdc_max_v", np.inf)) | (pesc < -tol) | ((pac > 0) & (pmech > pac + tol)))
    out["feasible"] = ~bad
    return out


def result_arrays_floor(vdc):
    """What returning the result costs without any model, allocated as dynosize.simulate allocates
    it: one (16, N) float64 block whose rows are the number columns, two bool arrays and the object
    array of limit names, each element written once."""
    block = np.empty((16, N))
    np.copyto(block, vdc)  # every row written once (broadcast)
    out = {k: block[k] for k in range(16)}
    for k in (16, 17):
        b = np.empty(N, dtype=bool)
        np.greater(vdc, 0.0, out=b)
        out[k] = b
    out[18] = np.full(N, "", dtype=object)
    return out


def cpp_per_point_s(exe):
    p = subprocess.run([exe, "--benchmark_filter=BM_SimulateColumnsInverse$", "--benchmark_format=json",
                        "--benchmark_repetitions=5"], capture_output=True, text=True, check=True)
    runs = [b for b in json.loads(p.stdout)["benchmarks"] if b.get("run_type") == "iteration"]
    return min(b["real_time"] * {"ms": 1e-3, "us": 1e-6, "ns": 1e-9}[b["time_unit"]] for b in runs) / N


def main():
    rng = np.random.default_rng(25)  # the C++ bench's ranges (bench/simulate_batch_bench.cc)
    vdc = 6.0 + 2.4 * rng.random(N)
    torque = 0.04 * rng.random(N)
    rpm = 2000.0 + 10000.0 * rng.random(N)
    cat = dynosize.Catalog()
    t_py, t_cpp = float("inf"), float("inf")
    for _ in range(ROUNDS):
        t, r = best_of(lambda: dynosize.simulate(motor=MOTOR, esc=ESC, vdc_v=vdc, torque_nm=torque, rpm=rpm,
                                                 catalog=cat))
        t_py = min(t_py, t)
        if len(sys.argv) > 1:
            t_cpp = min(t_cpp, cpp_per_point_s(sys.argv[1]))
    m, e = cat.show(MOTOR), cat.show(ESC)
    # The SI values the model uses (catalog show's derived values and the entries' own).
    m = dict(m, ke_v_s_per_rad=m["derived"]["ke_v_s_per_rad"], kt_nm_per_a=m["derived"]["kt_nm_per_a"])
    t_np, ref = best_of(lambda: numpy_inverse(m, e, vdc, torque, rpm))
    t_floor, _ = best_of(lambda: result_arrays_floor(vdc))
    worst = max(float(np.max(np.abs(ref[k] - r[k]) / np.maximum(np.abs(r[k]), 1e-12))) for k in ref if k != "feasible")
    same_feasible = bool(np.array_equal(ref["feasible"], r["feasible"]))
    print(f"{N} points, best of {ROUNDS} x {REPEATS} (Python, numpy) and {ROUNDS} x 5 (C++):")
    print(f"  dynosize.simulate (Python): {1e9 * t_py / N:7.1f} ns per point ({1e3 * t_py:.1f} ms)")
    print(f"  numpy, the same equations:  {1e9 * t_np / N:7.1f} ns per point ({1e3 * t_np:.1f} ms);"
          f" numpy / dynosize = {t_np / t_py:.2f} (goal >= 5)")
    print(f"  the result arrays alone, allocated and written once: {1e9 * t_floor / N:7.1f} ns per point;"
          f" numpy / that = {t_np / t_floor:.2f} (the most numpy / dynosize can be)")
    print(f"  numpy vs dynosize: largest relative difference {worst:.1e}, feasible flags equal: {same_feasible}")
    if len(sys.argv) > 1:
        print(f"  C++ batch (api::SimulateColumns): {1e9 * t_cpp:7.1f} ns per point;"
              f" Python / C++ = {t_py / N / t_cpp:.2f} (goal <= 1.5); numpy / C++ = {t_np / N / t_cpp:.2f}")


if __name__ == "__main__":
    main()
