"""dynosize: the motor + ESC model, catalog, calibration and sizing engine as a Python module.

Every function takes keyword arguments named like the CLI's flags and returns what the CLI
prints with --json (simulate: a dict of numpy arrays). See docs/python.md.
"""
from ._dynosize import (  # noqa: F401
    Catalog,
    Error,
    __version__,
    bundled_catalog_dir,
    calibrate,
    diagnose,
    evaluate,
    optimize,
    simulate,
)

import os as _os
import time as _time

from ._dynosize import _sweep_document, _sweep_local, _sweep_plan, _sweep_point

from ._dynosize import _set_package_catalog_dir

# Installed by `cmake --install` (PREFIX/lib/python3.X/dist-packages/dynosize), the bundled catalog
# is PREFIX/share/dynosize/catalog (catalog/catalog_path.h, step 4 of BundledCatalogDir).
_prefix = _os.path.abspath(_os.path.join(_os.path.dirname(__file__), "..", "..", "..", ".."))
if _os.path.isdir(_os.path.join(_prefix, "share", "dynosize", "catalog")):
    _set_package_catalog_dir(_os.path.join(_prefix, "share", "dynosize", "catalog"))



def sweep(mission, grid, *, top=1, variants=False, threads=2, catalog=None, client=None, yes=False):
    """A trade study: the mission over the full-factorial grid, one search per point.

    mission: a mission file's path or its content as a dict. grid: {KEY: values}, KEY a JSON path
    into the mission ("vehicle.mass_kg", "segments[2].duration_s"), values a list or a string as
    --vary takes it ("START:STOP:STEP", "v1,v2"). Returns the dict of `dynosize sweep --json`
    (its "rows" in grid order, the last key varying fastest).

    client: a dask.distributed Client. Each grid point is then one task on its cluster (the
    catalog is loaded once per worker process); the rows equal the local ones. Without it the
    points run on `threads` threads here. A grid over 10^6 points needs yes=True.
    """
    plan = _sweep_plan(mission, grid, yes)
    if client is None:
        return _sweep_local(plan, top=top, variants=variants, threads=threads, catalog=catalog)
    spec = None if catalog is None else catalog._spec
    t0 = _time.monotonic()
    futures = client.map(_sweep_task, range(plan["points"]), plan=plan, top=top, variants=variants, spec=spec,
                         pure=False)
    rows = client.gather(futures)
    return _sweep_document(plan, rows, _time.monotonic() - t0)


# Catalogs loaded by this (worker) process, by their folders: each is loaded once.
_worker_catalogs = {}


def _sweep_task(index, plan, top, variants, spec):
    """One grid point of a distributed sweep (runs on a dask worker)."""
    catalog = None
    if spec is not None:
        key = (spec[0], tuple(spec[1]), bool(spec[2]))
        if key not in _worker_catalogs:
            _worker_catalogs[key] = Catalog(spec[0], list(spec[1]), bool(spec[2]))
        catalog = _worker_catalogs[key]
    return _sweep_point(plan, index, top=top, variants=variants, catalog=catalog)


__all__ = ["Catalog", "Error", "bundled_catalog_dir", "calibrate", "diagnose", "evaluate", "optimize",
           "simulate", "sweep"]
