"""Every notebook in ``notebooks/`` runs top to bottom at reduced size (``PAS_NB_SMALL=1``).

The kernel imports the same ``pas`` as this test process (its ``src`` folder
is put first on the kernel's ``PYTHONPATH``), draws with the inline (Agg) backend, and runs
in a temporary working directory so the notebooks' files land there.
"""

import os
from pathlib import Path

import pytest

import pas

nbformat = pytest.importorskip("nbformat", reason="notebook tests need the dev extra")
nbclient = pytest.importorskip("nbclient", reason="notebook tests need the dev extra")

NOTEBOOKS = sorted((Path(__file__).resolve().parents[2] / "notebooks").glob("*.ipynb"))


def test_notebooks_are_there():
    names = [p.name for p in NOTEBOOKS]
    assert names == ["01_quickstart.ipynb", "02_validation_cases.ipynb",
                     "03_external_hf_results.ipynb", "04_impact_statistics.ipynb",
                     "05_long_term.ipynb"]


@pytest.mark.slow
@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_notebook_runs(path, tmp_path, monkeypatch):
    nb = nbformat.read(path, as_version=4)
    # the parameters cell must honour PAS_NB_SMALL, so CI can run it small
    params = [c for c in nb.cells if "parameters" in c.metadata.get("tags", [])]
    assert params and "PAS_NB_SMALL" in params[0].source
    src = str(Path(pas.__file__).resolve().parents[1])
    monkeypatch.setenv("PAS_NB_SMALL", "1")
    # the kernel's inline backend (Agg rendering to PNG outputs), never a display
    monkeypatch.delenv("MPLBACKEND", raising=False)
    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.setenv("PYTHONPATH", os.pathsep.join(
        [src] + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p]))
    client = nbclient.NotebookClient(nb, timeout=300, kernel_name="python3",
                                     resources={"metadata": {"path": str(tmp_path)}})
    client.execute()
    # no cell raised (nbclient raises CellExecutionError otherwise); figures were drawn
    outputs = [o for c in nb.cells if c.cell_type == "code" for o in c.get("outputs", [])]
    assert not [o for o in outputs if o.get("output_type") == "error"]
    images = [o for o in outputs if "image/png" in o.get("data", {})]
    assert len(images) >= 3, f"{path.name} drew {len(images)} figure(s)"
