"""optimize on a mission nothing flies: the dict says why (no_design_because, docs/search.md#why-nothing-flies)."""
import json

import dynosize

QUAD = "examples/missions/quadcopter_1p5kg.json"


def heavy_quad(repo, mass_kg):
    mission = json.loads((repo / QUAD).read_text())
    mission["vehicle"]["mass_kg"] = mass_kg
    return mission


def test_a_150_kg_quadcopter_says_why_nothing_flies(catalog, repo):
    got = dynosize.optimize(heavy_quad(repo, 150.0), top=1, catalog=catalog)
    assert got["results"] == []
    reasons = got["no_design_because"]
    assert reasons, got
    for r in reasons:
        assert {"requirement", "needed", "best_available", "unit", "components"} <= set(r)
        assert r["needed"] > r["best_available"], r
    names = [r["requirement"] for r in reasons]
    assert "hover_thrust_per_rotor" in names
    thrust = reasons[names.index("hover_thrust_per_rotor")]
    assert thrust["unit"] == "N"
    assert thrust["needed"] >= 150.0 * 9.80665 / 4  # the vehicle alone over 4 rotors
    assert len(thrust["components"]) == 2  # the best motor and propeller


def test_a_mission_that_flies_gives_no_reasons(catalog, repo):
    got = dynosize.optimize(str(repo / QUAD), top=1, catalog=catalog)
    assert got["results"]
    assert got["no_design_because"] == []
