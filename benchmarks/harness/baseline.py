"""A baseline revision's ``src`` unpacked beside this tree, for timing scripts that compare."""

import subprocess
import tarfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def baseline_tree(commit, into):
    """``src`` of ``commit`` (``git archive``) unpacked in ``into``; returns its path."""
    archive = Path(into) / "src.tar"
    with open(archive, "wb") as f:
        subprocess.run(["git", "-C", str(ROOT), "archive", commit, "src"], stdout=f, check=True)
    with tarfile.open(archive) as tar:
        tar.extractall(into, filter="data")
    return Path(into) / "src"
