"""Helpers below every layer, with no other ``pas`` import: argument checks
(:mod:`.checks`), strict JSON (:mod:`.strict_json`), lazy package exports
(:mod:`.lazy`) and one BLAS thread for small linear algebra (:mod:`.threads`)."""
