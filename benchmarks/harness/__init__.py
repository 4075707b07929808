"""What the benchmark scripts share: not part of the installed package.

The generated problems with exact truths (:mod:`harness.known_truth`, its held-out
types and :mod:`harness.known_truth_runs`, the studies run on them), the timing
problem (:mod:`harness.timing_problem`), PAS's estimator refitted to chosen events
(:mod:`harness.refits`), the reference estimators of "what k impact loads can
tell" (:mod:`harness.references`), the CFD scripts' sea recipe and top-N errors
(:mod:`harness.cfd`), the long-term data sets pooled (:mod:`harness.long_term_data_sets`)
and the tables the scripts write into the result pages (:mod:`harness.result_tables`,
:mod:`harness.error_tables`).

The scripts put ``benchmarks/`` on ``sys.path`` to import it; the tests find it
through pytest's ``pythonpath`` (``pyproject.toml``).
"""
