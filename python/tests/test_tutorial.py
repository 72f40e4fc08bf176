"""The tutorial (docs/tutorial.py, shown in docs/tutorial.md) runs, on a small packing."""

import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def test_tutorial_runs(tmp_path):
    result = subprocess.run([sys.executable, os.path.join(ROOT, "docs", "tutorial.py"), str(tmp_path), "--small"],
                            capture_output=True, text=True, env=dict(os.environ, MPLBACKEND="Agg", OMP_NUM_THREADS="1"))
    assert result.returncode == 0, result.stderr
    for name in ["ls.xyz", "relaxed.vtu", "bonded.vtu", "tutorial-relax.png", "tutorial-coordination.png",
                 "tutorial-rdf.png"]:
        assert (tmp_path / name).exists(), name
    assert "bonds" in result.stdout
