"""examples/python/quickstart.py runs to the end (the notebook-style example of docs/python.md)."""
import os
import subprocess
import sys


def test_quickstart_example_runs(repo, tmp_path):
    import dynosize
    # The module this test imports, for the example's own interpreter (PYTHONPATH may be relative).
    package_dir = os.path.dirname(os.path.dirname(os.path.abspath(dynosize.__file__)))
    env = dict(os.environ, MPLBACKEND="Agg", PYTHONPATH=package_dir)
    p = subprocess.run([sys.executable, str(repo / "examples" / "python" / "quickstart.py")], cwd=tmp_path, env=env,
                       capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stderr
    assert "best design" in p.stdout
