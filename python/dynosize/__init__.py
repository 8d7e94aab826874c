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

__all__ = ["Catalog", "Error", "bundled_catalog_dir", "calibrate", "diagnose", "evaluate", "optimize",
           "simulate"]
