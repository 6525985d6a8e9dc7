"""EHD film thickness (docs/model.md §6.3): NVM asymptotes and agreement with Hamrock-Dowson.

The NVM law is written once, in logarithms (dynamics/lubrication/film_laws/nvm.py); the tests
hold it against the formula as published, with powers, written out here (`nvm_asymptotes`,
`nvm_central_dimensionless`: Nijenbanning, Venner & Moes, Wear 176 (1994) 217-229, as in
docs/model.md §6.3), so that the two are independent statements of one law."""

import math

import numpy as np
import pytest

from bearingsim.dynamics.lubrication import film
from bearingsim.dynamics.lubrication.film_laws import LAWS, operations
from bearingsim.dynamics.lubrication.film_laws.hamrock_dowson import HamrockDowson, film_hamrock_dowson
from bearingsim.dynamics.lubrication.film_laws.nvm import (
    NVM, central_film_from_terms, film_central_nvm, geometry_terms,
)
from bearingsim.dynamics.lubrication.lubricant import load_builtin_lubricant
from tests.lubrication_points import E_EFF, curvature_radii, rolling_speed


def nvm_asymptotes(M, L, lam):
    """The four Moes asymptotes (H_RI, H_EI, H_RP, H_EP), written with powers."""
    c = 1.0 + 0.006 * math.log(lam) + 0.63 * lam ** (4.0 / 7.0)
    H_RI = 145.0 * (1.0 + 0.796 * lam ** (14.0 / 15.0)) ** (-15.0 / 7.0) / lam / (M * M)
    H_EI = 3.18 * c ** (-14.0 / 25.0) * lam ** (-1.0 / 15.0) * M ** (-2.0 / 15.0)
    H_RP = 1.29 * (1.0 + 0.691 * lam) ** (-2.0 / 3.0) * L ** (2.0 / 3.0)
    H_EP = 1.48 * c ** (-7.0 / 20.0) * lam ** (-1.0 / 24.0) * M ** (-1.0 / 12.0) * L**0.75
    return H_RI, H_EI, H_RP, H_EP


def nvm_central_dimensionless(M, L, lam):
    """H_c of the blend, written with powers; H_00 = 1.8/lambda; L = 0 is isoviscous."""
    H_RI, H_EI, H_RP, H_EP = nvm_asymptotes(M, L, lam)
    H_00 = 1.8 / lam
    s = 1.5 * (1.0 + math.exp(-1.2 * H_EI / H_RI))
    iso = (H_RI**1.5 + (H_EI**-4.0 + H_00**-4.0) ** -0.375) ** (2.0 * s / 3.0)
    piezo = (H_RP**-8.0 + H_EP**-8.0) ** (-s / 8.0) if L > 0.0 else 0.0
    return (iso + piezo) ** (1.0 / s)


def film_central_nvm_direct(F, Rx, Ry, E_eff, eta0, alpha_p, u_s):
    """h_c [m] from the dimensionless groups, written with powers."""
    speed = eta0 * u_s / (E_eff * Rx)
    M = F / (E_eff * Rx * Rx) * speed**-0.75
    L = alpha_p * E_eff * speed**0.25
    return nvm_central_dimensionless(M, L, Rx / Ry) * Rx * math.sqrt(speed)

# Regimes of the Moes diagram (Nijenbanning, Venner & Moes, Wear 176 (1994), Fig. 1 and the
# asymptotes quoted in docs/model.md §6.3): each (M, L) pair is deep in one regime, chosen so the
# other asymptotes are at least ~50x away in the blending formula.
REGIMES = {
    "RI": (0.01, 0.0),     # rigid-isoviscous: small load parameter, no piezoviscosity
    "EI": (1e6, 0.0),      # elastic-isoviscous: large M, L = 0
    "RP": (0.5, 1e12),     # rigid-piezoviscous: small M, huge L (H_RP << H_EP, >> H_RI)
    "EP": (1e8, 1e4),      # elastic-piezoviscous: large M and L, H_EP << H_RP
}


@pytest.mark.parametrize("regime", list(REGIMES))
@pytest.mark.parametrize("lam", [0.05, 0.3, 1.0])
def test_nvm_recovers_each_asymptote_in_its_regime(regime, lam):
    M, L = REGIMES[regime]
    H_RI, H_EI, H_RP, H_EP = nvm_asymptotes(M, L, lam)
    asymptote = {"RI": H_RI, "EI": H_EI, "RP": H_RP, "EP": H_EP}[regime]
    assert nvm_central_dimensionless(M, L, lam) == pytest.approx(asymptote, rel=0.01)


def test_nvm_ep_regime_has_the_moes_exponents():
    # H_EP ~ M^-1/12 L^3/4 (docs/model.md §6.3) -> dimensional h_c ~ u_s^0.75 F^-1/12 deep in EP
    M0, L0, lam = 1e8, 1e4, 0.1
    H0 = nvm_central_dimensionless(M0, L0, lam)
    s = 2.0  # doubling u_s: M -> M s^-3/4, L -> L s^1/4, h -> H sqrt(s)
    H1 = nvm_central_dimensionless(M0 * s**-0.75, L0 * s**0.25, lam)
    assert math.log(H1 * math.sqrt(s) / H0) / math.log(s) == pytest.approx(0.75, abs=0.01)


def test_nvm_within_25_percent_of_hamrock_dowson_for_reference_bearing():
    # docs/model.md §6.3 acceptance: NVM central film within +-25 % of Hamrock & Dowson (1977)
    lub = load_builtin_lubricant("nato-o156")
    eta0, alpha = lub.eta0, lub.alpha_star
    worst = 0.0
    for race in ("inner", "outer"):
        for angle in (25.0, 30.0, 35.0):
            Rx, Ry = curvature_radii(race, angle)
            for F in (100.0, 300.0, 1000.0, 3000.0, 6000.0):
                for speed in (0.1, 0.5, 1.0, 2.0):
                    u_s = 2.0 * rolling_speed(angle, speed)
                    h_nvm = film_central_nvm(F, Rx, Ry, E_EFF, eta0, alpha, u_s)
                    h_c, h_min = film_hamrock_dowson(F, Rx, Ry, E_EFF, eta0, alpha, u_s)
                    assert 0.0 < h_min < h_c
                    worst = max(worst, abs(h_nvm / h_c - 1.0))
    assert worst < 0.25
    print(f"max |NVM/HD - 1| over the reference bearing: {worst:.3f}")


def test_hamrock_dowson_exponents_and_limits():
    # the 1977 fit: h_c ~ u^0.67 alpha^0.53 F^-0.067; no load or no speed -> no film
    args = dict(Rx=0.007, Ry=0.2, E_eff=E_EFF, eta0=0.005, alpha_p=1e-8)
    base = film_hamrock_dowson(F=1000.0, u_s=20.0, **args)[0]
    assert film_hamrock_dowson(F=1000.0, u_s=40.0, **args)[0] / base == pytest.approx(2**0.67, rel=1e-12)
    assert film_hamrock_dowson(F=8000.0, u_s=20.0, **args)[0] / base == pytest.approx(8**-0.067, rel=1e-12)
    assert film_hamrock_dowson(F=0.0, u_s=20.0, **args) == (0.0, 0.0)
    assert film_central_nvm(1000.0, 0.007, 0.2, E_EFF, 0.005, 1e-8, 0.0) == 0.0


def test_h00_choice_does_not_matter_for_reference_contacts():
    # M >~ 100 for the reference bearing: the H_00 cap is inactive (module docstring claim)
    M, L, lam = 200.0, 6.5, 0.02
    H_RI, H_EI, H_RP, H_EP = nvm_asymptotes(M, L, lam)
    for H00 in (0.9 / lam, 3.6 / lam):
        capped = (H_EI**-4 + H00**-4) ** -0.25
        assert capped == pytest.approx(H_EI, rel=1e-3)


def test_film_kernels_equal_py_func_on_random_inputs():
    rng = np.random.default_rng(7)
    for _ in range(40):
        args = (rng.uniform(50, 8000), rng.uniform(0.003, 0.012), rng.uniform(0.05, 1.0), E_EFF,
                rng.uniform(1e-3, 0.05), rng.uniform(5e-9, 3e-8), rng.uniform(0.5, 60))
        assert film_central_nvm(*args) == pytest.approx(film_central_nvm.py_func(*args), rel=1e-12)
        hc, hm = film_hamrock_dowson(*args)
        hc2, hm2 = film_hamrock_dowson.py_func(*args)
        assert (hc, hm) == (pytest.approx(hc2, rel=1e-12), pytest.approx(hm2, rel=1e-12))
        # the registry's route reaches the same functions
        assert operations.central_film(NVM(), *args) == film_central_nvm(*args)
        assert operations.central_film(HamrockDowson(), *args) == hc
    assert set(LAWS) >= {"nvm", "hamrock-dowson"}


def test_log_space_nvm_equals_the_direct_formula():
    # film_central_nvm (the law) works on logarithms; film_central_nvm_direct (above) writes the
    # same §6.3 formula with powers. Over all four regimes (loads 1e-2..1e5 N, speeds
    # 1e-3..100 m/s, lambda 0.005..2, isoviscous and piezoviscous) they agree to rounding.
    rng = np.random.default_rng(11)
    logu = lambda lo, hi: math.exp(rng.uniform(math.log(lo), math.log(hi)))  # noqa: E731
    for _ in range(3000):
        Rx = logu(1e-4, 0.05)
        args = (logu(1e-2, 1e5), Rx, Rx / logu(0.005, 2.0), E_EFF, logu(1e-3, 1.0),
                rng.choice([0.0, logu(5e-9, 3e-8)]), logu(1e-3, 100.0))
        direct = film_central_nvm_direct(*args)
        assert direct > 0.0
        assert film_central_nvm(*args) == pytest.approx(direct, rel=1e-10), args


def test_batch_nvm_equals_the_one_contact_kernel():
    # film_central_nvm_batch (the time loop: all contacts at once, exp and log vectorised in
    # dynamics._speed.simd_math) against the law's central_film_from_terms, contact by contact,
    # over the same four regimes as above: the same stages, so agreement to rounding.
    rng = np.random.default_rng(17)
    logu = lambda lo, hi: np.exp(rng.uniform(math.log(lo), math.log(hi), n))  # noqa: E731
    n = 3000
    Rx = logu(1e-4, 0.05)
    F, Ry, u_s = logu(1e-2, 1e5), Rx / logu(0.005, 2.0), logu(1e-3, 100.0)
    eta0 = 0.02
    terms = np.array([geometry_terms(Rx[i], Ry[i]) for i in range(n)]).T.copy()
    for alpha_p in (0.0, 1.5e-8):
        h = np.full(n, np.nan)
        film.film_central_nvm_batch(np.array([F, Rx, u_s, *terms]), n, E_EFF, eta0, alpha_p, h,
                                    np.empty((film.FILM_BATCH_ROWS, 5 * n)), np.empty(5 * n, dtype=np.int64))
        one = [central_film_from_terms(F[i], Rx[i], E_EFF, eta0, alpha_p, u_s[i], tuple(terms[:, i])) for i in range(n)]
        np.testing.assert_allclose(h, one, rtol=1e-12)
