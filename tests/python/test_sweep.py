"""dynosize.sweep: the rows of `dynosize sweep --json`, locally and as dask tasks, and its bad input."""
import pytest

import dynosize

from conftest import SOURCE_DIR, run_cli

QUAD = str(SOURCE_DIR / "examples" / "missions" / "quadcopter_1p5kg.json")
# Two points of the quadcopter example (a few seconds each way on 2 cores).
GRID = {"battery.capacity_ah": [3, 5]}


def without_seconds(doc):
    return {k: v for k, v in doc.items() if k != "seconds"}


def test_sweep_equals_the_cli():
    py = dynosize.sweep(QUAD, GRID)
    cli = run_cli("sweep", QUAD, "--vary", "battery.capacity_ah=3,5", "--json", "--quiet")
    assert cli.code == 0, cli.err
    assert without_seconds(py) == without_seconds(cli.json())
    assert py["points"] == 2 and py["done"] == 2 and py["failed"] == 0
    assert [r["values"]["battery.capacity_ah"] for r in py["rows"]] == [3, 5]
    # A larger pack flies longer on this quadcopter: the rows are real searches, not copies.
    assert py["rows"][1]["picks"][0]["objective"] > py["rows"][0]["picks"][0]["objective"]


def test_grid_strings_as_vary_takes_them():
    by_list = dynosize.sweep(QUAD, {"vehicle.mass_kg": [0.5, 0.75]})
    by_range = dynosize.sweep(QUAD, {"vehicle.mass_kg": "0.5:0.75:0.25"})
    assert by_list["rows"] == by_range["rows"]


def test_a_dask_cluster_gives_the_local_rows():
    distributed = pytest.importorskip("distributed")
    local = dynosize.sweep(QUAD, GRID)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        remote = dynosize.sweep(QUAD, GRID, client=client)
        # Two worker processes, each loading the catalog once (dynosize._sweep_task).
        assert len(client.scheduler_info()["workers"]) == 2
    assert remote["rows"] == local["rows"]
    assert without_seconds(remote) == without_seconds(local)


def test_a_catalog_object_reaches_the_workers():
    distributed = pytest.importorskip("distributed")
    cat = dynosize.Catalog()
    local = dynosize.sweep(QUAD, GRID, catalog=cat)
    with distributed.Client(processes=False, n_workers=1, threads_per_worker=2, dashboard_address=None) as client:
        remote = dynosize.sweep(QUAD, GRID, catalog=cat, client=client)
    assert remote["rows"] == local["rows"]


@pytest.mark.parametrize("grid, cli_vary", [
    ({"vehicle.masz_kg": [1.0]}, "vehicle.masz_kg=1.0"),
    ({"vehicle.mass_kg": "0.5:1.0:0"}, "vehicle.mass_kg=0.5:1.0:0"),
    ({"segments": [1]}, "segments=1"),
])
def test_bad_keys_raise_the_clis_message(grid, cli_vary):
    cli = run_cli("sweep", QUAD, "--vary", cli_vary)
    assert cli.code == 64
    with pytest.raises(ValueError) as e:
        dynosize.sweep(QUAD, grid)
    assert str(e.value) == cli.message()


def test_a_grid_over_a_million_points_needs_yes():
    grid = {"vehicle.mass_kg": "0.001:1.001:0.001", "vehicle.rotors": "1:1000:1"}
    with pytest.raises(ValueError, match="over 10\\^6"):
        dynosize.sweep(QUAD, grid)


def test_a_missing_mission_is_file_not_found():
    with pytest.raises(FileNotFoundError):
        dynosize.sweep(str(SOURCE_DIR / "no_such_mission.json"), GRID)
