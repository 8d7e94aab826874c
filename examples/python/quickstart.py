"""dynosize from Python, notebook style: load the catalog, simulate an array of throttles, then
evaluate and optimize the quadcopter example. Run from anywhere (docs/python.md):

    PYTHONPATH=build/python /usr/bin/python3 examples/python/quickstart.py

(or without PYTHONPATH once `cmake --install` has put the module on the Python path).
"""
import pathlib

import numpy as np

import dynosize

HERE = pathlib.Path(__file__).resolve().parent
MISSION = HERE.parent / "missions" / "quadcopter_1p5kg.json"

# %% 1. The catalog, loaded once and passed to every call.
catalog = dynosize.Catalog()
print(f"catalog: {len(catalog)} entries from {', '.join(catalog.folders)}")
motor = catalog.show("emax_1900kv_paper")
print(f"motor {motor['id']}: KE {motor['derived']['ke_v_s_per_rad']:.5f} V*s/rad")

# %% 2. The paper's pair on a hysteresis brake: 0.02 N*m at 7.2 V, throttle 20 % to 100 %.
throttle = np.linspace(0.2, 1.0, 9)
r = dynosize.simulate(motor="emax_1900kv_paper", esc="multistar_30a_paper", vdc_v=7.2, throttle=throttle,
                      torque_nm=0.02, catalog=catalog)
print("\n  TR %     rpm   IDC A   PDC W  eta_sys %  feasible")
for i in range(len(throttle)):
    print(f"{100 * r['throttle'][i]:6.0f} {r['rpm'][i]:7.0f} {r['idc_a'][i]:7.2f} {r['pdc_w'][i]:7.1f}"
          f" {100 * r['eta_system'][i]:10.1f}  {'yes' if r['feasible'][i] else r['limits'][i]}")
try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots()
    ax.plot(r["rpm"], 100 * r["eta_system"], marker="o")
    ax.set_xlabel("speed, rpm")
    ax.set_ylabel("system efficiency, %")
    ax.set_title("emax 1900 kV + Multistar 30 A, 7.2 V, 0.02 N*m")
    fig.savefig("quickstart_efficiency.png", dpi=100)
    print("wrote quickstart_efficiency.png")
except ImportError:
    pass  # matplotlib is optional: the table above says the same

# %% 3. One combination flying the quadcopter's mission (evaluate), then the catalog's best (optimize).
e = dynosize.evaluate(str(MISSION), motor="dc_m_365", esc="dc_e_56", prop="dc_p_231", battery="dc_b_363", cells=4,
                      catalog=catalog)
print(f"\nevaluate: {e['objective']:.0f} {e['objective_unit']} ({e['objective_type']}), feasible: {e['feasible']}")
o = dynosize.optimize(str(MISSION), top=3, catalog=catalog)
for rank, best in enumerate(o["results"], 1):
    print(f"best design #{rank}: {best['motor']} + {best['esc']} + {best['prop']} + {best['cells']}S {best['battery']}:"
          f" {best['objective']:.0f} {best['objective_unit']}")
