"""dynosize.simulate: arrays through the batch path, the CLI's JSON keys and numbers."""
import numpy as np
import pytest

import dynosize

MOTOR = "emax_1900kv_paper"
ESC = "multistar_30a_paper"
POINT_KEYS = {"vdc_v", "throttle", "throttle_effective", "rpm", "omega_rad_s", "torque_nm", "irms_a", "vll_rms_v",
              "pac_w", "idc_a", "pdc_w", "pesc_w", "pmech_w", "eta_motor", "eta_esc", "eta_system", "saturated",
              "feasible", "limits"}


def _cli_point(cli, *args):
    j = cli("simulate", "--motor", MOTOR, "--esc", ESC, "--json", *args).json()
    return j


@pytest.mark.parametrize("flags,kwargs", [
    (("--vdc", 7.2, "--throttle", 0.6, "--torque", 0.02), dict(vdc_v=7.2, throttle=0.6, torque_nm=0.02)),
    (("--vdc", 7.2, "--throttle", 0.6, "--rpm", 9000), dict(vdc_v=7.2, throttle=0.6, rpm=9000)),
    (("--vdc", 7.2, "--torque", 0.02, "--rpm", 9000), dict(vdc_v=7.2, torque_nm=0.02, rpm=9000)),
    (("--vdc", 11.1, "--throttle", 1.0, "--torque", 0.3), dict(vdc_v=11.1, throttle=1.0, torque_nm=0.3)),
    # Past the limits: above the knee, stalled, an inversion above 100 % throttle, over the ESC's volts.
    (("--vdc", 7.2, "--throttle", 0.95, "--rpm", 3000), dict(vdc_v=7.2, throttle=0.95, rpm=3000)),
    (("--vdc", 7.2, "--throttle", 0.3, "--torque", 0.2), dict(vdc_v=7.2, throttle=0.3, torque_nm=0.2)),
    (("--vdc", 7.2, "--torque", 0.03, "--rpm", 14000), dict(vdc_v=7.2, torque_nm=0.03, rpm=14000)),
    (("--vdc", 20, "--torque", 0.01, "--rpm", 5000), dict(vdc_v=20.0, torque_nm=0.01, rpm=5000)),
])
def test_scalar_point_equals_cli_json(catalog, cli, flags, kwargs):
    got = dynosize.simulate(motor=MOTOR, esc=ESC, catalog=catalog, **kwargs)
    want = _cli_point(cli, *flags)
    assert set(got) == POINT_KEYS
    for key in POINT_KEYS - {"limits"}:
        assert got[key].shape == (1,)
        assert got[key][0] == want[key], key  # the same code path: equal to the last bit
    assert got["limits"][0] == ";".join(want["limits"])


def test_arrays_equal_points_one_by_one(catalog):
    rng = np.random.default_rng(25)  # seeded: deterministic
    n = 200
    throttle = rng.uniform(0.1, 1.0, n)
    torque = rng.uniform(0.0, 0.2, n)
    batch = dynosize.simulate(motor=MOTOR, esc=ESC, vdc_v=7.2, throttle=throttle, torque_nm=torque, catalog=catalog)
    for i in (0, 17, n - 1):
        one = dynosize.simulate(motor=MOTOR, esc=ESC, vdc_v=7.2, throttle=throttle[i], torque_nm=torque[i],
                                catalog=catalog)
        for key in POINT_KEYS:
            assert batch[key][i] == one[key][0], key
    assert batch["rpm"].shape == (n,) and batch["feasible"].dtype == bool
    # Some points overload the pair: flagged, never hidden.
    assert (~batch["feasible"]).any() and all(batch["limits"][~batch["feasible"]])


def test_batch_csv_equals_cli_batch(catalog, cli, repo):
    import csv
    import io
    rows = list(csv.DictReader(io.StringIO(cli("simulate", "--motor", MOTOR, "--esc", ESC, "--batch",
                                               "examples/points.csv").out)))
    src = list(csv.DictReader(open(repo / "examples" / "points.csv")))
    for r, s in zip(rows, src):
        kw = {k: float(s[k]) for k in ("throttle", "torque_nm", "rpm") if s.get(k)}
        got = dynosize.simulate(motor=MOTOR, esc=ESC, vdc_v=float(s["vdc_v"]), catalog=catalog, **kw)
        for key in ("rpm", "idc_a", "pdc_w", "eta_system"):
            # The CSV prints 10 significant digits (io/points_csv.h): compare at that precision.
            assert got[key][0] == pytest.approx(float(r[key]), rel=1e-9, abs=1e-9), key


def test_propeller_rows(catalog, cli):
    thrust = np.array([2.0, 5.0])
    got = dynosize.simulate(motor="dc_m_365", esc="dc_e_56", prop="dc_p_231", vdc_v=14.8, thrust_n=thrust,
                            catalog=catalog)
    assert got["thrust_n"] == pytest.approx(thrust, rel=1e-6)
    assert set(got) == POINT_KEYS | {"thrust_n", "g_per_w"}
    assert (got["g_per_w"] > 0).all()
    with pytest.raises(ValueError, match="point:0: a row with a prop takes its load from the propeller"):
        dynosize.simulate(motor="dc_m_365", esc="dc_e_56", prop="dc_p_231", vdc_v=14.8, throttle=0.5, torque_nm=0.1)
    with pytest.raises(ValueError, match="no_such_prop"):
        dynosize.simulate(motor="dc_m_365", esc="dc_e_56", prop="no_such_prop", vdc_v=14.8, throttle=0.5)


def test_errors_carry_the_cli_message(catalog, cli):
    with pytest.raises(ValueError) as e:
        dynosize.simulate(motor="nope", esc=ESC, vdc_v=7.2, throttle=0.5, torque_nm=0.01, catalog=catalog)
    assert str(e.value) == cli("simulate", "--motor", "nope", "--esc", ESC, "--vdc", 7).message()
    with pytest.raises(ValueError, match="vdc_v|VDC"):
        dynosize.simulate(motor=MOTOR, esc=ESC, vdc_v=-1.0, throttle=0.5, torque_nm=0.01, catalog=catalog)
    with pytest.raises(ValueError, match="throttle: 3 values where the other arrays have 2"):
        dynosize.simulate(motor=MOTOR, esc=ESC, vdc_v=[7.0, 7.2], throttle=[0.1, 0.2, 0.3], torque_nm=0.01)
    with pytest.raises(ValueError):
        dynosize.simulate(motor=MOTOR, esc=ESC, vdc_v=7.2, throttle=0.5)  # no load given


def test_bad_arrays_one_clear_line(catalog):
    # NaN is out of every range: the first such point, its key, value and rule.
    with pytest.raises(ValueError, match=r"^simulate: point:1: vdc_v = nan: must be > 0 V and <= 100000 V$"):
        dynosize.simulate(motor=MOTOR, esc=ESC, vdc_v=[7.2, np.nan], torque_nm=0.01, rpm=5000, catalog=catalog)
    with pytest.raises(ValueError, match=r"^simulate: point:2: torque_nm = nan: must be >= 0 N\*m"):
        dynosize.simulate(motor=MOTOR, esc=ESC, vdc_v=7.2, torque_nm=[0.01, 0.02, np.nan], rpm=5000, catalog=catalog)
    with pytest.raises(ValueError, match=r"^simulate: point:0: rpm = nan"):
        dynosize.simulate(motor=MOTOR, esc=ESC, vdc_v=7.2, torque_nm=[0.01, 0.02], rpm=np.nan, catalog=catalog)
    # Shapes that do not broadcast.
    with pytest.raises(ValueError, match=r"^rpm: give a number or a 1-D array$"):
        dynosize.simulate(motor=MOTOR, esc=ESC, vdc_v=7.2, torque_nm=0.01, rpm=np.ones((2, 3)), catalog=catalog)
    with pytest.raises(ValueError, match=r"^rpm: 3 values where the other arrays have 2$"):
        dynosize.simulate(motor=MOTOR, esc=ESC, vdc_v=[7.0, 7.2], torque_nm=0.01, rpm=[1.0, 2.0, 3.0], catalog=catalog)


def test_large_batch_is_written_in_place(catalog):
    # More points than one chunk of the batch, every key a contiguous, writeable 1-D array (the
    # numbers are rows of one block, docs/python.md "Performance").
    rng = np.random.default_rng(3)
    n = 5000
    got = dynosize.simulate(motor=MOTOR, esc=ESC, vdc_v=rng.uniform(6, 20, n), torque_nm=rng.uniform(0, 0.1, n),
                            rpm=rng.uniform(0, 20000, n), catalog=catalog)
    for key in POINT_KEYS:
        assert got[key].shape == (n,) and got[key].flags.c_contiguous and got[key].flags.writeable, key
    assert got["feasible"].dtype == bool and got["limits"].dtype == object
    assert set(got["limits"][~got["feasible"]]) >= {"throttle_above_one", "esc_voltage"}
    assert (got["limits"][got["feasible"]] == "").all()
    # The throttle that holds each point reproduces it through the forward model (eq 49).
    fwd = dynosize.simulate(motor=MOTOR, esc=ESC, vdc_v=got["vdc_v"], throttle=np.clip(got["throttle"], 0, 1),
                            rpm=got["rpm"], catalog=catalog)
    ok = (got["throttle"] >= 0) & (got["throttle"] <= 1)
    # 1e-9: the inverse and the forward model round a dozen operations differently (1e-15 each).
    assert fwd["torque_nm"][ok] == pytest.approx(got["torque_nm"][ok], rel=1e-9, abs=1e-12)
    got["pdc_w"][:] = 0.0  # a column written in place leaves its neighbours alone
    assert (got["idc_a"] != 0).any() and (got["pac_w"] != 0).any()
