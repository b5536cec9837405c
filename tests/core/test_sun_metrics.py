"""cDA, ASE, LM-83 operable blinds and simplified DGP (climate/sun_metrics.py) against
answers counted by hand on small constructed arrays, with values placed exactly on the
thresholds to pin each comparison (> or >=) to its published wording."""

from __future__ import annotations

import math

import numpy as np
import pytest

from lightinv_core.climate.sun_metrics import (
    DGP_CLASS_NAMES,
    ase,
    blinds_closed,
    blinds_schedule,
    continuous_da,
    dgp_class,
    dgp_ev,
    dgp_exceedance,
    dgp_simplified,
    direct_sun_share,
    glare_protection,
    lux_with_blinds,
    sda_with_blinds,
)
from lightinv_core.errors import LightInvError


def test_cda_full_credit_at_threshold_and_partial_below():
    lux = np.array([[0.0, 150.0, 300.0, 600.0], [30.0, 60.0, 90.0, 120.0]])
    # point 0: 0 + 0.5 + 1 + 1 over 4 hours; point 1: (0.1 + 0.2 + 0.3 + 0.4) / 4
    assert continuous_da(lux) == pytest.approx([0.625, 0.25])
    assert continuous_da(lux, threshold=150.0) == pytest.approx([0.75, 0.5])


def test_cda_equals_da_where_light_is_all_or_nothing():
    rng = np.random.default_rng(3)
    lux = np.where(rng.random((20, 50)) < 0.4, 0.0, 800.0)
    assert continuous_da(lux) == pytest.approx((lux >= 300).mean(axis=1))


def test_cda_rejects_bad_input():
    with pytest.raises(LightInvError):
        continuous_da(np.ones(5))
    with pytest.raises(LightInvError):
        continuous_da(np.ones((2, 2)), threshold=0.0)
    with pytest.raises(LightInvError):
        continuous_da(np.array([[1.0, np.nan]]))


def test_ase_strict_on_both_thresholds():
    t = 300
    direct = np.zeros((4, t))
    direct[0, :251] = 1001.0  # 251 h above 1000 lux: more than 250 -> counts
    direct[1, :250] = 1001.0  # exactly 250 h: not more than 250 -> does not count
    direct[2, :] = 1000.0  # exactly 1000 lux does not exceed 1000
    direct[3, :260] = 5000.0
    result = ase(direct)
    assert result.hours.tolist() == [251, 250, 0, 260]
    assert result.share == 0.5
    assert ase(direct, hours=249).share == 0.75
    assert ase(direct, lux=999.0).share == 0.75  # point 2 now above for 300 h


def test_direct_sun_is_1000_lux_or_more_and_blinds_close_above_two_percent():
    direct = np.zeros((100, 4))
    direct[:2, 0] = 1000.0  # 2 points at exactly 1000 lux: 2%, not more than 2%
    direct[:3, 1] = 1000.0  # 3%: closed
    direct[:3, 2] = 999.9  # below 1000: no direct sun
    direct[:, 3] = 20000.0
    assert direct_sun_share(direct).tolist() == [0.02, 0.03, 0.0, 1.0]
    assert blinds_closed(direct).tolist() == [False, True, False, True]
    assert blinds_closed(direct, share=0.03).tolist() == [False, False, False, True]


def _two_groups():
    """Two glazing groups, 100 points, 5 hours, each hour a case counted by hand."""
    a = np.zeros((100, 5))
    b = np.zeros((100, 5))
    a[:5, 1] = 2000.0  # hour 1: A puts 5% in sun -> close A only
    a[:5, 2] = 2000.0  # hour 2: A 5%, B 5% -> closing one leaves 5%: close both
    b[50:55, 2] = 2000.0
    a[:1, 3] = 2000.0  # hour 3: A 1%, B 2%: closing either meets the rule; closing
    b[50:52, 3] = 2000.0  # A leaves more sun in (2%), so A is closed
    a[90:93, 4] = 600.0  # hour 4: neither alone reaches 1000 lux, together 1200 on
    b[90:93, 4] = 600.0  # 3%: one group must close (group 0 first at a tie)
    return np.stack([a, b])


def test_blinds_schedule_lm83_combinations_by_hand():
    closed = blinds_schedule(_two_groups())
    assert closed.tolist() == [
        [False, True, True, True, True],
        [False, False, True, False, False],
    ]
    # Judged apart (each group's own sun), hour 4 would close nothing: the sum matters.
    apart = np.stack([blinds_closed(g) for g in _two_groups()])
    assert apart[:, 4].tolist() == [False, False]


def test_blinds_closed_state_may_still_let_sun_in():
    direct = _two_groups()
    leaky = direct * 0.6  # closed blinds passing 60% of the beam
    closed = blinds_schedule(direct, leaky)
    # hour 2: both closed still leaves 5% + 5% of points at 1200 lux: nothing meets
    # the rule, so everything is closed; hour 4: 0.6 * 600 + 600 < 1000 after one.
    assert closed[:, 2].tolist() == [True, True]
    assert closed[:, 4].tolist() == [True, False]


def test_one_group_schedule_is_the_single_group_rule():
    rng = np.random.default_rng(1)
    direct = np.where(rng.random((1, 200, 80)) < 0.03, 3000.0, 0.0)
    assert (blinds_schedule(direct)[0] == blinds_closed(direct[0])).all()


def test_greedy_matches_exhaustive_on_disjoint_groups():
    rng = np.random.default_rng(7)
    groups, q, t = 5, 200, 60
    direct = np.zeros((groups, q, t))
    for g in range(groups):  # each group lights its own 40 points, a random number each hour
        lit = rng.integers(0, 12, size=t)
        for h in range(t):
            direct[g, g * 40 : g * 40 + lit[h], h] = 1500.0
    ex = blinds_schedule(direct, method="exhaustive")
    gr = blinds_schedule(direct, method="greedy")
    assert (ex.sum(axis=0) == gr.sum(axis=0)).all()  # as few groups closed
    for closed in (ex, gr):
        after = (np.where(closed[:, None, :], 0.0, direct).sum(axis=0) >= 1000).mean(axis=0)
        assert (after <= 0.02).all()


def test_lux_with_blinds_mixes_each_groups_state():
    open_parts = np.array([[[100.0, 200.0, 300.0]], [[10.0, 20.0, 30.0]]])  # G=2, q=1, T=3
    closed_parts = np.array([[[1.0, 2.0, 3.0]], [[0.5, 0.5, 0.5]]])
    closed = np.array([[False, True, True], [True, False, True]])
    assert lux_with_blinds(open_parts, closed_parts, closed).tolist() == [[100.5, 22.0, 3.5]]
    with pytest.raises(LightInvError):
        lux_with_blinds(open_parts, closed_parts, closed[:, :2])


def test_sda_with_blinds_counts_the_light_of_the_chosen_states():
    direct = np.zeros((1, 4, 4))
    direct[0, 0, 2:] = 5000.0  # 25% of points in sun in hours 2 and 3: blinds close
    open_parts = np.full((1, 4, 4), 400.0) + direct
    closed_parts = np.full((1, 4, 4), 100.0)
    result = sda_with_blinds(open_parts, closed_parts, direct)
    assert result.closed.tolist() == [[False, False, True, True]]
    assert result.da.tolist() == [0.5, 0.5, 0.5, 0.5]  # 400 lux in hours 0-1 only
    assert result.sda == 1.0
    assert result.closed_share.tolist() == [0.5]


def test_dgp_simplified_is_wienolds_line():
    ev = np.array([0.0, 1000.0, 2500.0, 5000.0, 20000.0])
    expected = [0.184, 0.0622 + 0.184, 0.1555 + 0.184, 0.311 + 0.184, 1.0]  # capped at 1
    assert dgp_simplified(ev) == pytest.approx(expected, abs=1e-12)
    assert dgp_ev(0.45) == pytest.approx((0.45 - 0.184) / 6.22e-5)
    assert dgp_simplified(dgp_ev(0.4)) == pytest.approx(0.4)


def test_low_light_correction_is_evalglares_factor():
    at = 4.0 / 0.024  # exp(0) / (1 + exp(0)) = 1/2
    base = dgp_simplified(np.array([at, 500.0, 1000.0, 3000.0]))
    corr = dgp_simplified(np.array([at, 500.0, 1000.0, 3000.0]), low_light_correction=True)
    factor_500 = math.exp(8.0) / (1 + math.exp(8.0))
    assert corr == pytest.approx([base[0] / 2, base[1] * factor_500, base[2], base[3]])


def test_dgp_classes_from_wienold():
    dgp = dgp_simplified(np.array([1500.0, 3000.0, 3700.0, 4500.0]))
    # 0.277, 0.371, 0.414, 0.464
    assert [DGP_CLASS_NAMES[i] for i in dgp_class(dgp)] == list(DGP_CLASS_NAMES)
    assert dgp_class(np.array([0.35, 0.40, 0.45])).tolist() == [1, 2, 3]


def test_exceedance_and_en17037_glare_levels_counted_by_hand():
    ev = np.full((3, 20), 1000.0)  # DGPs 0.246: imperceptible
    ev[0, 0] = 5000.0  # view 0: 1 hour of 20 above 0.45 (5%): still meets each level
    ev[1, :2] = 5000.0  # view 1: 2 hours (10%) above 0.45: none
    ev[2, :1] = 3700.0  # view 2: 1 hour at 0.414 and 1 at 0.371: above 0.35 in 10%
    ev[2, 1] = 3000.0
    assert dgp_exceedance(ev, 0.45).tolist() == [0.05, 0.10, 0.0]
    assert dgp_exceedance(ev, 0.35).tolist() == [0.05, 0.10, 0.10]
    glare = glare_protection(ev)
    assert glare.level == ("high", "none", "medium")
    assert glare.exceedance.shape == (3, 3)


def test_greedy_keeps_closing_when_one_group_alone_changes_nothing():
    # Six groups each give 250 lux on the same 3% of the points: closing one or two
    # leaves 1250 or 1000 lux (no fewer points in sun); three must close.
    direct = np.zeros((6, 100, 1))
    direct[:, :3, 0] = 250.0
    for method in ("greedy", "exhaustive"):
        closed = blinds_schedule(direct, method=method)
        assert closed[:, 0].tolist() == [True, True, True, False, False, False], method


def test_a_view_exactly_at_the_limit_does_not_exceed_it():
    at = float(dgp_simplified(1000.0))
    ev = np.array([[1000.0, 1000.0, 1000.1, 0.0]])
    assert dgp_exceedance(ev, at).tolist() == [0.25]
    assert dgp_exceedance(np.zeros((2, 3)), 0.184).tolist() == [0.0, 0.0]
