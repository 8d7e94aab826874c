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

from ._dynosize import _set_package_catalog_dir

# Installed by `cmake --install` (PREFIX/lib/python3.X/dist-packages/dynosize), the bundled catalog
# is PREFIX/share/dynosize/catalog (catalog/catalog_path.h, step 4 of BundledCatalogDir).
_prefix = _os.path.abspath(_os.path.join(_os.path.dirname(__file__), "..", "..", "..", ".."))
if _os.path.isdir(_os.path.join(_prefix, "share", "dynosize", "catalog")):
    _set_package_catalog_dir(_os.path.join(_prefix, "share", "dynosize", "catalog"))

__all__ = ["Catalog", "Error", "bundled_catalog_dir", "calibrate", "diagnose", "evaluate", "optimize",
           "simulate"]
