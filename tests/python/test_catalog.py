"""dynosize.Catalog: the same entries as `catalog list --json` and `catalog show`, user folders on top."""
import json

import pytest

import dynosize

MOTOR = "emax_1900kv_paper"
ESC = "multistar_30a_paper"


def test_list_by_kind_is_catalog_list_json(catalog, cli):
    for kind in ("escs", "batteries"):
        assert catalog.list(kind) == cli("catalog", "list", "--kind", kind, "--json").json()[kind]


def test_list_filters_are_the_cli_flags(catalog, cli):
    got = catalog.list("motors", kv_min=1000, kv_max=1500)
    assert got == cli("catalog", "list", "--kind", "motors", "--kv-min", 1000, "--kv-max", 1500, "--json").json()["motors"]
    assert got and all(1000 <= m["kv_rpm_per_v"] <= 1500 for m in got)


def test_list_all_kinds(catalog):
    everything = catalog.list()
    assert set(everything) == {"motors", "escs", "props", "batteries"}
    assert sum(len(v) for v in everything.values()) == len(catalog)


def test_show_is_catalog_show(catalog, cli):
    for entry in (MOTOR, ESC, "dc_b_363"):
        assert catalog.show(entry) == json.loads(cli("catalog", "show", entry).out)


def test_unknown_id_is_value_error_with_cli_message(catalog, cli):
    with pytest.raises(ValueError) as e:
        catalog.show("no_such_part")
    assert str(e.value) == cli("catalog", "show", "no_such_part").message()


def test_bad_filter_is_value_error(catalog, cli):
    with pytest.raises(ValueError) as e:
        catalog.list("motors", kv_min=-1)
    assert str(e.value) == cli("catalog", "list", "--kv-min", -1).message()


def _own_part(folder, motor_id, io_a_times_1e4):
    entry = dict(dynosize.Catalog().show(MOTOR))
    for key in ("derived", "in_system"):
        entry.pop(key, None)
    entry["id"] = motor_id
    entry["io_a"] = io_a_times_1e4 / 1e4  # a value to find the entry by (the bundled one's io_a differs)
    (folder / "mine.json").write_text(json.dumps({"motors": [entry]}))


def test_add_folder_on_top_and_clash(tmp_path, cli):
    cat = dynosize.Catalog()
    n = len(cat)
    own = tmp_path / "own"
    own.mkdir()
    _own_part(own, "my_motor_1", 1500)
    cat.add(str(own))
    assert len(cat) == n + 1
    assert cat.show("my_motor_1")["io_a"] == 0.15
    # The same id as a bundled entry: an error naming both files, as --catalog-add.
    clash = tmp_path / "clash"
    clash.mkdir()
    _own_part(clash, MOTOR, 1500)
    with pytest.raises(ValueError) as e:
        dynosize.Catalog(add=[str(clash)])
    assert str(e.value) == cli("--catalog-add", clash, "catalog", "show", MOTOR).message()
    assert "mine.json" in str(e.value) and "paper_brown_chopra.json" in str(e.value)
    # override=True lets the added entry win.
    assert dynosize.Catalog(add=[str(clash)], override=True).show(MOTOR)["io_a"] == 0.15


def test_missing_folder_is_file_not_found(tmp_path):
    with pytest.raises(FileNotFoundError):
        dynosize.Catalog(str(tmp_path / "nothing_here"))
