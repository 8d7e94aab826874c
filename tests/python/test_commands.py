"""evaluate, optimize, calibrate, diagnose: the same dicts as the CLI's --json on the examples."""
import pytest

import dynosize

QUAD = "examples/missions/quadcopter_1p5kg.json"
PICK = dict(motor="dc_m_365", esc="dc_e_56", prop="dc_p_231", battery="dc_b_363", cells=4)


def test_evaluate_equals_cli_json(catalog, cli, repo):
    got = dynosize.evaluate(str(repo / QUAD), catalog=catalog, **PICK)
    want = cli("evaluate", QUAD, "--motor", "dc_m_365", "--esc", "dc_e_56", "--prop", "dc_p_231", "--battery",
               "dc_b_363", "--cells", 4, "--json").json()
    assert got == want


def test_evaluate_mission_as_dict(catalog, repo):
    import json
    mission = json.loads((repo / QUAD).read_text())
    assert dynosize.evaluate(mission, catalog=catalog, **PICK)["objective"] == \
        dynosize.evaluate(str(repo / QUAD), catalog=catalog, **PICK)["objective"]


def test_optimize_equals_cli_json(catalog, cli, repo):
    got = dynosize.optimize(str(repo / QUAD), top=3, catalog=catalog)
    want = cli("optimize", QUAD, "--top", 3, "--json", "--quiet").json()
    got.pop("seconds")
    want.pop("seconds")  # wall time, the only key that differs between runs
    assert got == want
    assert len(got["results"]) == 3


def test_calibrate_equals_cli_json(cli, repo):
    got = dynosize.calibrate([str(repo / "examples/dyno_log.csv")], motor_id="my_motor", esc_id="my_esc")
    want = cli("calibrate", "examples/dyno_log.csv", "--motor-id", "my_motor", "--esc-id", "my_esc", "--json").json()
    assert got == want
    assert got["status"] == "ok"


def test_diagnose_equals_cli_json(catalog, cli, repo):
    got = dynosize.diagnose(str(repo / "examples/dyno_log.csv"), motor="emax_1900kv_paper",
                            esc="multistar_30a_paper", catalog=catalog)
    want = cli("diagnose", repo / "examples/dyno_log.csv", "--motor", "emax_1900kv_paper", "--esc", "multistar_30a_paper",
               "--json").json()
    assert got == want


@pytest.mark.parametrize("call,args", [
    (lambda r: dynosize.evaluate(str(r / QUAD), motor="dc_m_365", esc="dc_e_56", prop="dc_p_231", battery="dc_b_363"),
     ("evaluate", QUAD, "--motor", "dc_m_365", "--esc", "dc_e_56", "--prop", "dc_p_231", "--battery", "dc_b_363")),
    (lambda r: dynosize.evaluate(str(r / QUAD), motor="dc_m_365", esc="dc_e_56", battery="dc_b_363"),
     ("evaluate", QUAD, "--motor", "dc_m_365", "--esc", "dc_e_56", "--battery", "dc_b_363")),
    (lambda r: dynosize.optimize(str(r / QUAD), time_limit_s=0),
     ("optimize", QUAD, "--time-limit", 0)),
    (lambda r: dynosize.calibrate([str(r / "examples/dyno_log.csv")], motor_id="m", esc_id="e", kv_label=-3),
     ("calibrate", "examples/dyno_log.csv", "--motor-id", "m", "--esc-id", "e", "--kv-label", -3)),
    (lambda r: dynosize.diagnose(str(r / "examples/dyno_log.csv"), kv_label=0),
     ("diagnose", "examples/dyno_log.csv", "--kv-label", 0)),
])
def test_bad_input_is_value_error_with_cli_message(cli, repo, call, args):
    run = cli(*args)
    assert run.code in (64, 65)
    with pytest.raises(ValueError) as e:
        call(repo)
    assert str(e.value) == run.message()


def test_missing_file_is_file_not_found(cli, repo):
    run = cli("diagnose", "no_such_log.csv")
    assert run.code == 66
    with pytest.raises(FileNotFoundError) as e:
        dynosize.diagnose(str(repo / "no_such_log.csv"))
    assert str(e.value).endswith(run.message().split(": ", 1)[1])
    with pytest.raises(FileNotFoundError):
        dynosize.optimize(str(repo / "no_such_mission.json"))


def test_error_class():
    assert issubclass(dynosize.Error, RuntimeError)


def test_optimize_with_sized_propellers_equals_cli_json(catalog, cli, repo):
    # A mission's sized propellers (docs/missions.md "sized_props") reach the search from Python too.
    mission = "examples/missions/air_taxi_sized_rotors.json"
    got = dynosize.optimize(str(repo / mission), top=1, catalog=catalog)
    want = cli("optimize", mission, "--top", 1, "--json", "--quiet").json()
    got.pop("seconds")
    want.pop("seconds")
    assert got == want
    assert "sized_multirotor_" in str(got["results"][0])
