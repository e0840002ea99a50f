import os
import subprocess

import numpy as np
import pytest


@pytest.fixture
def hush_program(tmp_path):
    """Runs the `hush` program (HUSH_CLI, set by CTest) and returns the .npy it wrote."""
    exe = os.environ.get("HUSH_CLI")
    if not exe or not os.path.exists(exe):
        pytest.skip("the hush program was not built (HUSH_CLI unset or missing)")

    def run(*args):
        out = tmp_path / "out.npy"
        subprocess.run([exe, *args, "--out", str(out)], check=True, capture_output=True)
        return np.load(out)

    return run
