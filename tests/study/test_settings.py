"""Settings as objects: the face's size, every keyword of pas 0.1 reachable, one
source of names, the paper preset, the lf_peaks table and the docs table."""

import dataclasses
import inspect
import json
import re
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import pas
from pas.strategies.flat import FLAT_NAMES, pas_kwargs
from pas.study.factory import STUDY_SETTINGS
from pas.study.flat import MOVED, from_flat, moved_table
from pas.study.schema import RESUMABLE, with_legacy_settings

ROOT = Path(__file__).parents[2]

# every keyword pas.run_pas took in pas 0.1 (main at 0e65ed2: its 20 explicit arguments,
# the 18 PAS settings and the study settings), written out here, not read from the code
OLD_KEYWORDS = [
    "lf_peaks", "oracle", "n_waves", "p_exp", "eps1", "eps2", "threshold", "seed", "max_hf",
    "ids", "meta", "batch_size", "callback", "study", "pending", "executor", "n_workers",
    "n_waves_convention", "preset", "retry_failed",
    "families", "z", "delta_aic", "exclude_at_bound", "upper_tail", "outlier_k", "n_bootstrap",
    "skip_unsplittable", "marginals_from", "impact_model", "estimator", "copula_fit",
    "common_random_numbers", "hf_location", "hf_marginal", "band_marginals", "band_lf_ranks",
    "lf_tail",
    "k1", "k2", "stop_measure", "max_failures", "stop_on_convergence", "adaptive_threshold",
    "threshold_step", "fp_run", "legacy_md", "target",
]
LF = np.random.default_rng(0).rayleigh(2.0, 600)


def _oracle(ev):
    return 1.2 * ev.lf ** 1.1


@pytest.mark.parametrize("run", [pas.run_pas, pas.run_as])
def test_the_run_functions_take_at_most_19_parameters(run):
    """Settings live in objects; the signature keeps the inputs, the shortcuts a user types and
    the run's own options (n_waves_convention, so a case's run_kwargs() passes)."""
    assert len(inspect.signature(run).parameters) <= 19


def test_a_case_run_kwargs_pass_to_run_pas():
    from pas.validation import generate_case

    d = generate_case("1a", seed=0)
    kw = d.run_kwargs()
    assert kw["n_waves_convention"] == "spectral" and kw["n_waves"] < d.lf.size
    res = pas.run_pas(d.lf_table(), d.oracle(), **kw, seed=1, max_hf=8,
                      strategy=pas.PAS(band=pas.ModelBand(n_bootstrap=0)))
    assert res.n_hf == 8


@pytest.mark.parametrize("name", OLD_KEYWORDS)
def test_every_old_keyword_is_an_argument_or_names_its_new_place_in_one_line(name):
    params = inspect.signature(pas.run_pas).parameters
    if name in params:
        return
    with pytest.raises(TypeError) as info:
        pas.run_pas(LF, _oracle, n_waves=600, p_exp=1e-2, eps1=0.1, **{name: 1})
    message = str(info.value)
    assert "\n" not in message
    assert message == (f"run_pas: {name} is now {MOVED[name]}; "
                       "see https://pas.readthedocs.io/reference/settings/")


def test_the_docs_table_is_the_mapping_the_errors_use():
    page = (ROOT / "docs" / "reference" / "settings.md").read_text(encoding="utf-8")
    table = re.search(r"<!-- table: pas.study.flat.moved_table\(\) -->\n(.*?)\n<!-- end of table",
                      page, re.S).group(1)
    assert table == moved_table()
    rows = dict(re.findall(r"^\| `(\w+)` \| `(.+)` \|$", table, re.M))
    assert rows == MOVED and len(rows) > 30


def test_conflicting_arguments_and_objects_are_one_line_errors():
    with pytest.raises(ValueError, match=r"^run_pas: give eps1, eps2 inside stopping=.*not both$"):
        pas.run_pas(LF, _oracle, n_waves=600, p_exp=1e-2, eps1=0.1, eps2=0.2,
                    stopping=pas.Stopping(eps1=0.1))
    with pytest.raises(ValueError, match=r"^run_pas: give max_hf inside budget="):
        pas.run_pas(LF, _oracle, n_waves=600, p_exp=1e-2, eps1=0.1, max_hf=None,
                    budget=pas.Budget())
    with pytest.raises(TypeError, match="stopping must be Stopping"):
        pas.run_pas(LF, _oracle, n_waves=600, p_exp=1e-2, stopping={"eps1": 0.1})
    with pytest.raises(TypeError, match=r"^PAS: n_bootstrap is now PAS\(band=ModelBand"):
        pas.PAS(n_bootstrap=0)


def test_arguments_and_objects_give_the_same_study():
    by_args = pas.make_study("pas", LF, n_waves=600, p_exp=1e-2, eps1=0.1, eps2=0.2, max_hf=30,
                             seed=4)
    by_objects = pas.make_study("pas", LF, n_waves=600, p_exp=1e-2, seed=4,
                                stopping=pas.Stopping(eps1=0.1, eps2=0.2),
                                budget=pas.Budget(max_hf=30))
    assert by_args.settings() == by_objects.settings()
    assert (by_args.rule.eps2, by_args.max_hf, by_args.max_failures) == (0.2, 30, 10)


def test_the_paper_preset_is_the_settings_of_pas_0_1():
    # pas 0.1's PRESETS["paper"] over its PAS defaults, written out (not read from the code)
    paper_flat = {
        "families": ["gaussian", "student", "clayton", "gumbel", "frank"], "z": 10,
        "delta_aic": 4.0, "exclude_at_bound": False, "upper_tail": None, "outlier_k": 3.0,
        "n_bootstrap": 0, "skip_unsplittable": False, "marginals_from": "kept",
        "impact_model": False, "estimator": "selected", "copula_fit": "itau",
        "common_random_numbers": False, "hf_location": True, "hf_marginal": "weibull",
        "band_marginals": "fitted", "band_lf_ranks": "fixed", "lf_tail": "ranks"}
    study = pas.make_study(pas.PAS.paper(), LF, n_waves=600, p_exp=1e-2, eps1=0.1, seed=1)
    s = study.settings()
    assert (s["stop_measure"], s["max_hf"]) == ("step", None)
    stored_by_0_1 = {"strategy": "pas", "strategy_settings": paper_flat}
    assert json.loads(json.dumps(s["strategy_settings"])) == with_legacy_settings(
        stored_by_0_1)["strategy_settings"]
    # the same PAS from the flat names, and the stopping/budget of the preset from_flat gives
    objects = from_flat({"eps1": 0.1}, preset="paper")
    assert objects["strategy"].settings() == pas.PAS.paper().settings()
    assert (objects["stopping"].measure, objects["budget"].max_hf) == ("step", None)
    # the strategy alone is only the model: its stopping and budget may be given
    given = pas.make_study(pas.PAS.paper(), LF, n_waves=600, p_exp=1e-2, eps1=0.1, max_hf=20)
    assert given.max_hf == 20 and given.rule.measure == "step"


def test_one_source_of_names():
    pas_fields = {f.name for cls in (pas.ConditionalLikelihood, pas.SelectedSample,
                                     pas.ModelBand) for f in dataclasses.fields(cls)}
    own = set(inspect.signature(pas.PAS).parameters) - {"estimator", "band", "moved"}
    band = {"marginals", "lf_ranks", "model_form"}
    assert set(FLAT_NAMES) == own | {"estimator"} | (pas_fields - band) \
        | {f"band_{name}" for name in band}
    stop_fields = {f.name for f in dataclasses.fields(pas.Stopping)}
    assert set(RESUMABLE) == (stop_fields - {"measure"}) | {"stop_measure", "max_hf",
                                                             "max_failures"}
    assert set(RESUMABLE) <= set(STUDY_SETTINGS)


def test_flat_settings_of_the_other_estimator_are_errors_or_dropped_from_a_store():
    with pytest.raises(ValueError, match="copula_fit is an option of estimator 'selected'"):
        pas_kwargs({"copula_fit": "itau"})
    kw = pas_kwargs({"copula_fit": "itau", "hf_marginal": "both"}, strict=False)
    assert kw["estimator"] == pas.ConditionalLikelihood(hf_marginal="both")
    with pytest.raises(ValueError, match="unknown setting 'zz' for PAS"):
        pas_kwargs({"zz": 1})


def test_a_table_carries_ids_and_meta_to_the_oracle():
    seen = []

    def oracle(ev):
        seen.append((ev.id, ev.meta))
        return 2.0 * ev.lf

    table = pd.DataFrame({"lf": LF, "seed": np.arange(600) + 100},
                         index=[f"ev{i}" for i in range(600)])
    pas.run_pas(table, oracle, n_waves=600, p_exp=1e-2, eps1=0.1, seed=0, max_hf=5,
                strategy=pas.PAS(band=pas.ModelBand(n_bootstrap=0)))
    assert len(seen) == 5
    assert all(meta == {"seed": int(i[2:]) + 100} for i, meta in seen)
    with_id_column = table.reset_index(names="id")
    study = pas.make_study("pas", with_id_column, n_waves=600, p_exp=1e-2, eps1=0.1, seed=0)
    assert study.ask(1)[0].id.startswith("ev")


def test_one_strategy_object_serves_two_studies_at_once():
    strategy = pas.PAS(band=pas.ModelBand(n_bootstrap=0))
    a = pas.make_study(strategy, LF, n_waves=600, p_exp=1e-2, eps1=0.1, seed=1)
    b = pas.make_study(strategy, LF, n_waves=600, p_exp=1e-2, eps1=0.1, seed=1)
    assert a.strategy is not b.strategy is not strategy
    for ev in a.ask(1):
        a.tell(ev, _oracle(ev))
    res_b = b.optimize(_oracle)
    res_a = a.optimize(_oracle)
    assert res_a.mpm == pytest.approx(res_b.mpm, rel=1e-12)


def test_resumed_python_study_keeps_what_pas_study_set_changed(tmp_path):
    """A default of run_pas never overwrites a stopping or budget value set on the store."""
    import numpy as np

    import pas
    from pas.cli import main
    from pas.study.store import StudyStore

    db = str(tmp_path / "c.db")
    lf = np.random.default_rng(1).rayleigh(1.0, 2000)

    def run(**kw):
        return pas.run_pas(lf, lambda e: 1.3 * e.lf ** 1.2, n_waves=2000, p_exp=1e-3,
                           eps1=0.05, seed=1, study=db,
                           strategy=pas.PAS(band=pas.ModelBand(n_bootstrap=0)), **kw)

    run(max_hf=12)
    assert main(["study", "set", db, "--max-hf", "18", "--eps2", "0.2", "--k2", "7"]) == 0
    result = run()
    with StudyStore(db, create=False) as store:
        kept = store.settings()
    assert (kept["max_hf"], kept["eps2"], kept["k2"]) == (18, 0.2, 7)
    assert result.n_hf <= 18
    run(eps2=0.1)  # named in the call: the new value replaces the stored one
    with StudyStore(db, create=False) as store:
        assert store.settings()["eps2"] == 0.1 and store.settings()["max_hf"] == 18


def test_the_n_waves_warning_points_at_the_users_line():
    lf = np.random.default_rng(0).rayleigh(1.0, 500)
    with pytest.warns(UserWarning, match="n_waves") as caught:
        pas.make_study(pas.PAS(), lf, n_waves=450, p_exp=1e-2, eps1=0.5, threshold=0.5)
    with pytest.warns(UserWarning, match="n_waves") as caught_run:
        pas.run_pas(lf, _oracle, n_waves=450, p_exp=1e-2, eps1=0.5, max_hf=4, threshold=0.5)
    assert {w.filename for w in [*caught, *caught_run] if "n_waves" in str(w.message)} == {
        __file__}
