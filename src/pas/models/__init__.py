"""Models of the LF–HF pairs: copulas, their densities, marginals and the joint fits.

:mod:`.copulas` (candidates, fits, AIC selection), :mod:`.copula_densities`
(closed-form log-densities), :mod:`.marginals`, and the joint conditional fits
of copula and HF marginal (:mod:`.joint`, :mod:`.joint_likelihood`,
:mod:`.joint_mixture`).  Nothing is imported here, so ``import pas`` stays fast.
"""
