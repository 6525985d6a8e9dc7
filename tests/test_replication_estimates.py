"""The closed-form estimates behind docs/replication.md §4 (benchmarks/replication/estimates.py)
against what they must give in limits and against sampling, and the page against its numbers:
docs/replication.md is what benchmarks/replication/page.py writes from
benchmarks/replication/data/replication.json."""

from __future__ import annotations

import importlib.util
import json
import math
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
Z = 22  # balls of the reference bearing (docs/model.md §2)


def _load(name: str):
    path = ROOT / "benchmarks" / "replication" / f"{name}.py"
    spec = importlib.util.spec_from_file_location(f"replication_{name}", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


est = _load("estimates")


def test_the_hertz_pattern_ratio_inverts_the_pattern():
    k = 0.3
    q = (1.0 + k * np.cos(np.linspace(0.0, 2.0 * math.pi, 721))) ** 1.5
    assert est.hertz_pattern_ratio(q.min(), q.max()) == pytest.approx(k, rel=1e-12)


@pytest.mark.parametrize("k", [0.3, 0.6])
def test_the_harmonics_of_the_hertz_pattern_fall_like_rho_to_the_n(k):
    """The Fourier coefficients of (1 + k cos psi)^(3/2) fall like n^(-5/2) rho^n, with
    rho = (1 - sqrt(1 - k^2))/k (k = 0.6: rho = 1/3): the function is analytic in a strip whose
    edge is the branch point cos psi = -1/k, of order 3/2 (Darboux's method). Their ratio at
    n = 12 against rho (n/(n+1))^(5/2)."""
    psi = np.linspace(0.0, 2.0 * math.pi, 4096, endpoint=False)
    c = np.abs(np.fft.rfft((1.0 + k * np.cos(psi)) ** 1.5)) / psi.size
    n = 12
    assert c[n + 1] / c[n] == pytest.approx(est.harmonic_decay(k) * (n / (n + 1)) ** 2.5, rel=0.02)
    assert est.harmonic_decay(0.6) == pytest.approx(1.0 / 3.0, rel=1e-12)


def test_varying_compliance_vanishes_with_every_ball_loaded_and_not_with_a_load_zone():
    """Every ball loaded (k < 1, the reference case b: 2.6-3.6 kN, k ~ 0.11): the radial force of
    22 evenly spaced balls does not vary over a ball pitch beyond round-off. A load zone that ends
    (k = 3: a third of the balls unloaded) makes it vary by a visible part of a ball load. A
    uniform pattern gives exactly nothing."""
    mean_load, alpha = 3000.0, math.radians(31.0)
    assert est.varying_compliance_force(0.0, Z, mean_load, alpha) < 1e-9
    loaded = est.varying_compliance_force(0.11, Z, mean_load, alpha)
    assert loaded < 1e-9 * Z * mean_load
    zone = est.varying_compliance_force(3.0, Z, mean_load, alpha)
    assert zone > 1e-3 * mean_load


def _reference_like_loads():
    psi = 2.0 * math.pi * np.arange(Z) / Z
    q = 3100.0 * (1.0 + 0.11 * np.cos(psi - math.pi)) ** 1.5
    alpha = math.radians(31.0) + math.radians(7.5) * np.cos(psi - math.pi)
    return psi, q, alpha


def test_ball_loads_balance_a_thrust_and_a_moment_of_the_right_signs():
    """Even loads at one contact angle give only -Fa along z (the balls push the race back against
    a +z thrust); heavier balls at psi = pi give a moment about -y, which balances a +y moment
    (docs/model.md §1: with +z thrust and a positive moment the most loaded ball is at pi)."""
    psi = 2.0 * math.pi * np.arange(Z) / Z
    even = est.ball_loads_on_inner_race(np.full(Z, 1000.0), np.full(Z, 0.5), psi, np.full(Z, 0.07))
    total = even.sum(axis=0)
    assert total[2] == pytest.approx(-Z * 1000.0 * math.sin(0.5))
    assert np.allclose(total[[0, 1, 3, 4]], 0.0, atol=1e-9)
    psi, q, alpha = _reference_like_loads()
    tilted = est.ball_loads_on_inner_race(q, alpha, psi, np.full(Z, 0.07)).sum(axis=0)
    assert tilted[4] < 0.0 and abs(tilted[3]) < 1e-9 * abs(tilted[4])


def test_the_scatter_estimate_is_the_rms_of_sampled_spacing_errors():
    """Independent spacing errors of rms sigma: the closed form sqrt(tr C S C^T) against the rms
    of C dF over many sampled sets of errors (dF = sum_j g_j delta_j)."""
    psi, q, alpha = _reference_like_loads()
    g = est.spacing_sensitivity(est.ball_loads_on_inner_race(q, alpha, psi, np.full(Z, 0.07)))
    k = np.diag([1.1e9, 1.1e9, 8.7e8, 2.6e6, 2.8e6])
    k[0, 4] = k[4, 0] = -5e7
    c = est.compliance(k, [1e9, 1e9, 1e9, 1e5, 1e5])
    sigma = 1e-3
    delta = np.random.default_rng(1).normal(0.0, sigma, (20000, Z))
    x = (delta @ g) @ c.T
    sampled = math.sqrt(np.mean(x[:, 0] ** 2 + x[:, 1] ** 2))
    assert est.scatter_radial_rms(g, c, sigma) == pytest.approx(sampled, rel=0.03)


def test_the_spacing_sensitivity_is_the_derivative_of_the_loads_along_the_orbit():
    psi, q, alpha = _reference_like_loads()
    r, h = np.full(Z, 0.07), 1e-7
    g = est.spacing_sensitivity(est.ball_loads_on_inner_race(q, alpha, psi, r))
    numeric = (est.ball_loads_on_inner_race(q, alpha, psi + h, r) - est.ball_loads_on_inner_race(q, alpha, psi - h, r)) / (2 * h)
    assert np.allclose(g, numeric, rtol=1e-6, atol=1e-6 * np.abs(numeric).max())


def test_spacing_deviation_keeps_only_what_is_not_fixed_in_space():
    """Balls turning together, each displaced by a pattern of its orbital position: no
    fluctuation is left. Add independent noise: its rms comes back."""
    rng = np.random.default_rng(2)
    t = np.linspace(0.0, 0.5, 4001)[:, None]
    base = 2.0 * math.pi * np.arange(Z) / Z + 143.7 * t
    pattern = 0.008 * np.sin(base)  # rad, fixed in space
    _, none = est.spacing_deviation(base + pattern)
    assert np.sqrt(np.mean(none ** 2)) < 0.02 * 0.008
    noise = rng.normal(0.0, 4e-4, base.shape)
    noise -= noise.mean(axis=1, keepdims=True)
    _, back = est.spacing_deviation(base + pattern + noise)
    assert np.sqrt(np.mean(back ** 2)) == pytest.approx(4e-4, rel=0.1)


def test_the_page_is_what_the_script_writes_from_its_numbers():
    """docs/replication.md is generated: `python -m benchmarks.replication --page-only` rewrites
    it from benchmarks/replication/data/replication.json."""
    page = _load("page")
    data = json.loads((ROOT / "benchmarks" / "replication" / "data" / "replication.json").read_text(encoding="utf-8"))
    assert (ROOT / "docs" / "replication.md").read_text(encoding="utf-8") == page.render(data)
