"""Peak extraction primitives against hand-computed arrays."""

import numpy as np
import pytest

from pas.stats import peaks as P

X = np.array([-1.0, 2.0, 1.0, -1.0, 0.0, 3.0, -2.0, -1.0, 4.0])


def test_zero_upcrossings_and_wave_extrema():
    np.testing.assert_array_equal(P.zero_upcrossings(X), [1, 4, 8])
    c, ci = P.wave_crests(X)
    tr, ti = P.wave_troughs(X)
    np.testing.assert_array_equal(c, [2.0, 3.0])
    np.testing.assert_array_equal(ci, [1, 5])
    np.testing.assert_array_equal(tr, [-1.0, -2.0])
    np.testing.assert_array_equal(ti, [3, 6])
    np.testing.assert_array_equal(P.zero_upcrossings(X, level=1.5), [1, 5, 8])


def test_segment_extrema_take_first_of_ties():
    v, i = P.segment_max([1.0, 3.0, 3.0, 0.0, 5.0, 5.0], [0, 3, 6])
    np.testing.assert_array_equal(v, [3.0, 5.0])
    np.testing.assert_array_equal(i, [1, 4])


def test_vectorised_crests_equal_a_plain_loop():
    rng = np.random.default_rng(0)
    x = np.convolve(rng.normal(size=5000), np.ones(15) / 15, mode="same")
    u = P.zero_upcrossings(x)
    c, ci = P.wave_crests(x)
    loop = [x[a:b].max() for a, b in zip(u[:-1], u[1:])]
    loop_i = [a + int(np.argmax(x[a:b])) for a, b in zip(u[:-1], u[1:])]
    np.testing.assert_array_equal(c, loop)
    np.testing.assert_array_equal(ci, loop_i)


def test_matched_peaks_use_lf_windows():
    lf = X
    hf = np.array([0.0, 0.5, 7.0, 0.0, 0.0, 1.0, 9.0, 0.0, 99.0])
    lv, hv, li, hi = P.matched_peaks(lf, hf)
    np.testing.assert_array_equal(lv, [2.0, 3.0])
    np.testing.assert_array_equal(hv, [7.0, 9.0])  # 99 lies after the last complete wave
    np.testing.assert_array_equal(hi, [2, 6])
    with pytest.raises(ValueError, match="same length"):
        P.matched_peaks(lf, hf[:-1])


def test_rise_time_and_velocity():
    t = np.arange(9.0) * 0.5
    rise, crest = P.rise_times(t, X)
    # wave 1: crossing at t = 0.5 * (0 + 1/3), crest at t = 0.5; wave 2: crossing at 2.0, crest at
    # 2.5
    np.testing.assert_allclose(rise, [0.5 - 0.5 / 3, 0.5])
    np.testing.assert_allclose(P.rise_velocities(t, X), [2.0 / (0.5 - 0.5 / 3), 3.0 / 0.5])
    np.testing.assert_allclose(P.upcrossing_times(t, X), [0.5 / 3, 2.0, 3.5 + 0.5 / 5])


def test_peaks_over_threshold():
    v, i = P.peaks_over_threshold([0, 2, 3, 1, 0, 5, 0, 0.2], 0.5)
    np.testing.assert_array_equal(v, [3.0, 5.0])
    np.testing.assert_array_equal(i, [2, 5])
    v, i = P.peaks_over_threshold([2, 3, 1, 0, 5, 6], 0.5)
    np.testing.assert_array_equal(v, [3.0, 6.0])
    np.testing.assert_array_equal(i, [1, 5])
    v, _ = P.peaks_over_threshold([2, 3, 1, 0, 5, 0, 6], 0.5, drop_incomplete=True)
    np.testing.assert_array_equal(v, [5.0])
    v, i = P.peaks_over_threshold([0.0, 0.1], 1.0)
    assert v.size == 0 and i.size == 0


def test_mask_near_joins():
    keep = P.mask_near_joins([1.0, 5.0, 9.5, 10.8, 11.2, 29.5], [10.0, 30.0], 1.0)
    np.testing.assert_array_equal(keep, [True, True, False, False, True, False])
    assert P.mask_near_joins([1.0], [], 5.0).all()


@pytest.mark.parametrize("bad", [[], [1.0], [0.0, np.nan, 1.0], [[0.0, 1.0], [1.0, 0.0]]])
def test_bad_input_is_refused(bad):
    with pytest.raises(ValueError):
        P.zero_upcrossings(bad)
    with pytest.raises(ValueError):
        P.wave_crests(bad)


def test_bad_segments_are_refused():
    with pytest.raises(ValueError, match="increasing"):
        P.segment_max([1.0, 2.0, 3.0], [0, 2, 1])
    with pytest.raises(ValueError):
        P.mask_near_joins([1.0], [0.0], -1.0)
