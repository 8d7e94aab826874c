#!/usr/bin/env python3
"""The heavy examples read as an engineer: runs `dynosize optimize --json --top 1` on each
mission and prints a Markdown table of the pick's disk loading, hover figure of merit, power
loading, tip Mach number, pack specific energy and every rating against its limit
(docs/missions.md, "Heavy-lift and eVTOL examples").

Usage: python3 scripts/heavy_examples.py [build/dynosize] > table.md

Figures, per the lift group's hover segment with the highest shaft power (its end point, the
worst case the report shows):
  disk loading   W/(n*A), A = pi*D^2/4 per rotor                       [N/m^2]
  figure of merit  T^1.5/sqrt(2*rho*A) / P_shaft  (docs/model.md section 10)
  power loading  T/P_shaft                                              [N/kW]
  tip Mach       pi*D*n/a, a = sqrt(1.4*287.05*T_air)
  pack           usable energy drawn over the pack's mass is not a property; the pack's
                 nominal energy (capacity x nominal voltage) over its mass         [Wh/kg]
"""
import json
import math
import subprocess
import sys

ROOT = __file__.rsplit("/scripts/", 1)[0]
MISSIONS = ["ag_octocopter_50kg", "cargo_octocopter_150kg", "air_taxi_one_seat", "air_taxi_sized_rotors"]


def load_catalog_entries():
    import glob
    entries = {}
    for f in glob.glob(ROOT + "/catalog/*.json"):
        doc = json.load(open(f))
        for kind in ("motors", "escs", "props", "batteries"):
            for e in doc.get(kind, []):
                entries[e["id"]] = e
    return entries


def rho_and_temp(mission):
    air = mission.get("air", {})
    if "density_kg_m3" in air:
        return air["density_kg_m3"], 15.0
    h = air.get("altitude_m", 0.0)
    t_c = air.get("temperature_c", 15.0)
    # ISA pressure at altitude h (troposphere), the mission's temperature: the same as
    # src/common/atmosphere.h for h and T.
    p = 101325.0 * (1.0 - 2.25577e-5 * h) ** 5.25588
    return p / (287.05 * (t_c + 273.15)), t_c


def lift_parts(result):
    if "groups" in result.get("motor", {}) if isinstance(result.get("motor"), dict) else False:
        return None
    return result


def figures(dynosize, name, cat):
    path = f"{ROOT}/examples/missions/{name}.json"
    mission = json.load(open(path))
    out = subprocess.run([dynosize, "optimize", path, "--top", "1", "--json", "--quiet"],
                         capture_output=True, text=True, check=True)
    doc = json.loads(out.stdout)
    if not doc["results"]:
        return {"mission": name, "none": doc.get("no_design_because", [])}
    r = doc["results"][0]
    rho, t_c = rho_and_temp(mission)
    sound = math.sqrt(1.4 * 287.05 * (t_c + 273.15))
    # The lift group's parts: a one-group mission names them at the top level, a lift+cruise one
    # per group (the first group lifts in the examples).
    motor, esc, prop = r["motor"], r["esc"], r["prop"]
    if isinstance(motor, dict):
        motor, esc, prop = motor["lift"], esc["lift"], prop["lift"]
    m, e, b = cat[motor], cat[esc], cat[r["battery"]]
    # A sized propeller (issue 52) is not in the catalog's files: the result states its size.
    sized = r.get("sized_prop") or r.get("groups", {}).get("lift", {}).get("sized_prop")
    d = sized["diameter_m"] if sized else cat[prop]["diameter_m"]
    area = math.pi * d * d / 4
    hovers = [s for s in r["segments"] if s["type"] in ("hover", "climb") and s.get("group", "lift") in ("lift", None)
              and s["thrust_per_rotor_n"] > 0]
    s = max(hovers, key=lambda x: x["pmech_w"])
    t = s["thrust_per_rotor_n"]
    p_ideal = t ** 1.5 / math.sqrt(2 * rho * area)
    n_rev_s = s["rpm"] / 60
    rotors = s["rotors"]
    weight = r["total_mass_kg"] * 9.80665
    cells = r["cells"]
    unit_cells = b.get("cells_series", 1) * b.get("cells_parallel", 1)
    pack_v = b["voltage_nominal_v"] / b.get("cells_series", 1) * cells
    ratio_cap = r["capacity_ah"] / b["capacity_ah"]
    parallel = mission["battery"].get("cells_parallel", 1)
    pack_mass = b["mass_kg"] * cells / b.get("cells_series", 1) * ratio_cap * mission["battery"].get("mass_factor", 1.0)
    worst = {k: max(x[k] for x in r["segments"] if x.get("group", "lift") in ("lift", None)) for k in ("irms_a", "pmech_w", "battery_current_a")}
    return {
        "mission": name, "pick": f"{motor} + {esc} + {prop}", "mass_kg": r["total_mass_kg"],
        "disk_loading": weight / (rotors * area), "fm": p_ideal / s["pmech_w"],
        "power_loading": t / (s["pmech_w"] / 1000), "tip_mach": math.pi * d * n_rev_s / sound,
        "segment": s["name"], "rpm": s["rpm"], "throttle": s["throttle"],
        "pack": f"{cells}S {r['battery']} {r['capacity_ah']:.1f} Ah",
        "pack_wh_per_kg": r["capacity_ah"] * pack_v / pack_mass,
        "motor_current": (worst["irms_a"], m.get("max_current_a")),
        "motor_power": (worst["pmech_w"], m.get("max_power_w")),
        "esc_current": (worst["irms_a"], e.get("max_current_a")),
        "t_w": r["thrust_to_weight"], "energy_wh": r["energy_wh"], "final_soc": r["final_soc"],
        "unit_cells": unit_cells, "parallel": parallel,
    }


def ratio(pair, unit):
    value, limit = pair
    if not limit:
        return f"{value:.0f} {unit} (no rating)"
    return f"{value:.0f} / {limit:.0f} {unit} ({100 * value / limit:.0f} %)"


def main():
    dynosize = sys.argv[1] if len(sys.argv) > 1 else ROOT + "/build/dynosize"
    cat = load_catalog_entries()
    rows = [figures(dynosize, n, cat) for n in MISSIONS]
    print("| mission | pick (lift group) | mass | disk loading | hover FM | power loading | tip Mach (rpm, throttle) "
          "| pack | pack Wh/kg (nominal) | motor current | motor shaft power | ESC current | T/W | energy, final SOC |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for f in rows:
        if "none" in f:
            print(f"| {f['mission']} | no design: " + "; ".join(x["requirement"] for x in f["none"]) + " |" + " |" * 12)
            continue
        print(f"| {f['mission']} | {f['pick']} | {f['mass_kg']:.1f} kg | {f['disk_loading']:.0f} N/m^2 | {f['fm']:.2f} "
              f"| {f['power_loading']:.1f} N/kW | {f['tip_mach']:.2f} ({f['rpm']:.0f} rpm, {100 * f['throttle']:.0f} %) "
              f"| {f['pack']} | {f['pack_wh_per_kg']:.0f} | {ratio(f['motor_current'], 'A')} | {ratio(f['motor_power'], 'W')} "
              f"| {ratio(f['esc_current'], 'A')} | {f['t_w']:.2f} | {f['energy_wh']:.0f} Wh, {100 * f['final_soc']:.0f} % |")


if __name__ == "__main__":
    main()
