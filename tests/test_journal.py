"""Cage–race short journal (docs/model.md §8): dynamics/journal/short_bearing.py, its land laws
(dynamics/journal/land_laws) and dynamics/journal/dry.py."""

import math

import numpy as np
import pytest
from scipy import integrate

from bearingsim.dynamics.geometry import BearingGeometry, CageGeometry, Material, effective_modulus
from bearingsim.dynamics.journal.short_bearing import (
    J_OUT_CONTACT_AZIMUTH,
    J_OUT_DF_DOMEGA_CAGE,
    J_OUT_DF_DOMEGA_RACE,
    J_OUT_DF_DPOS,
    J_OUT_DF_DVEL,
    J_OUT_DT_DOMEGA_CAGE,
    J_OUT_DT_DOMEGA_RACE,
    J_OUT_DT_DPOS,
    J_OUT_DT_DVEL,
    J_OUT_EPS,
    J_OUT_FRICTION_POWER,
    J_OUT_METAL_FORCE,
    J_OUT_TORQUE,
    cage_race_journal,
    JournalGeometry,
    journal_parameters,
    journal_parameters_for_cage,
    journal_scalars,
    ocvirk_force,
    ocvirk_torque,
    unpack_journal,
)
from bearingsim.dynamics.journal.land_laws.hybrid import hybrid_weights
from bearingsim.dynamics.journal.dry import lundberg_compliance, lundberg_deflection, lundberg_load, palmgren_load

STEEL = Material(208e9, 0.3, 7850.0)  # docs/model.md §2 scene values
BRONZE = Material(110e9, 0.34, 8800.0)
E_BRONZE_STEEL = effective_modulus(BRONZE, STEEL)

# Spec check case, docs/model.md §8 (short bearing): mu, omega, R, L, C.
MU, OMEGA, R_S, L_S, C_S = 0.01, 100.0, 0.05, 0.01, 1e-4


def params(**kw):
    base = dict(radius=R_S, length=L_S, clearance=C_S, viscosity=MU,
                effective_modulus=E_BRONZE_STEEL, friction_coefficient=0.1)
    base.update(kw)
    lands = JournalGeometry(**{name: base.pop(name) for name in JournalGeometry._fields if name in base})
    return journal_parameters(lands, **base)


def journal_at(eps, p, omega_cage=OMEGA, omega_race=0.0, azimuth=0.0, velocity=(0.0, 0.0)):
    e = eps * p.clearance
    offset = np.array([e * math.cos(azimuth), e * math.sin(azimuth)])
    return cage_race_journal(offset, np.array(velocity, dtype=float), omega_cage, omega_race, p)


# --- hydrodynamic part -------------------------------------------------------------------
def test_spec_short_bearing_check_values():
    # docs/model.md §8 check: F_n = 2.2222 N, F_t = 3.0230 N, attitude 53.68° (eps = 0.5)
    f_n, f_t, _, _ = ocvirk_force(0.5, MU, OMEGA, R_S, L_S, C_S)
    assert f_n == pytest.approx(2.2222, abs=5e-5)
    assert f_t == pytest.approx(3.0230, abs=5e-5)
    assert math.degrees(math.atan2(f_t, f_n)) == pytest.approx(53.68, abs=5e-3)
    # the full kernel, film only with clearance C, cage offset along +x
    out = journal_at(0.5, params(mode="hydrodynamic"))
    assert out[0] == pytest.approx(-2.2222, abs=5e-5)  # -F_n e_r
    assert out[1] == pytest.approx(3.0230, abs=5e-5)  # +F_t e_t, e_t = e_z x e_r = +y


def short_bearing_pressure(theta, z, eps):
    """Ocvirk short-bearing pressure, theta from the widest gap in the sense of rotation.

    p = (3 mu omega / C^2)(L^2/4 - z^2) eps sin(theta) / (1 + eps cos(theta))^3: Reynolds'
    equation without the circumferential pressure flow (Ocvirk, NACA TN 2808, 1952;
    Hamrock, Schmid & Jacobson, Fundamentals of Fluid Film Lubrication, 2nd ed. 2004,
    ch. 10, short-width journal bearing).
    """
    return 3 * MU * OMEGA / C_S**2 * (L_S**2 / 4 - z**2) * eps * math.sin(theta) / (1 + eps * math.cos(theta)) ** 3


@pytest.mark.parametrize("eps", [0.1, 0.5, 0.8, 0.95])
def test_ocvirk_against_pressure_integration(eps):
    # Gümbel: integrate the positive half 0 < theta < pi only. On the journal the pressure
    # pushes along (cos theta, sin theta) in (e_r, e_t) axes, theta = azimuth - (phi_e + pi).
    opts = dict(epsabs=0.0, epsrel=1e-11)
    f_r, _ = integrate.dblquad(lambda z, th: short_bearing_pressure(th, z, eps) * math.cos(th) * R_S,
                               0.0, math.pi, -L_S / 2, L_S / 2, **opts)
    f_t, _ = integrate.dblquad(lambda z, th: short_bearing_pressure(th, z, eps) * math.sin(th) * R_S,
                               0.0, math.pi, -L_S / 2, L_S / 2, **opts)
    f_n, f_t_closed, _, _ = ocvirk_force(eps, MU, OMEGA, R_S, L_S, C_S)
    assert -f_r == pytest.approx(f_n, rel=1e-8)
    assert f_t == pytest.approx(f_t_closed, rel=1e-8)


@pytest.mark.parametrize("eps", [0.0, 0.3, 0.7, 0.95])
def test_torque_against_shear_integration(eps):
    # Couette shear mu omega R / h on the full film (0 < theta < pi) and on the striated film
    # of the cavitated half, which carries the flux U h_min / 2, i.e. fills h_min/h of the gap.
    h = lambda th: C_S * (1 + eps * math.cos(th))
    h_min = C_S * (1 - eps)
    full, _ = integrate.quad(lambda th: 1 / h(th), 0.0, math.pi, epsabs=0, epsrel=1e-12)
    striated, _ = integrate.quad(lambda th: h_min / h(th) ** 2, math.pi, 2 * math.pi, epsabs=0, epsrel=1e-12)
    torque = MU * OMEGA * R_S * R_S * L_S * R_S * (full + striated)
    t, _ = ocvirk_torque(eps, MU, OMEGA, R_S, L_S, C_S)
    assert -t == pytest.approx(torque, rel=1e-9)


def test_torque_petroff_limit():
    # Petroff (1883): T = 2 pi mu omega R^3 L / C for a concentric full film
    # (Hamrock, Schmid & Jacobson 2004, ch. 10, Petroff's equation).
    t, _ = ocvirk_torque(0.0, MU, OMEGA, R_S, L_S, C_S)
    assert -t == pytest.approx(2 * math.pi * MU * OMEGA * R_S**3 * L_S / C_S, rel=1e-14)


def test_ocvirk_slopes_against_finite_differences():
    for eps in (0.05, 0.4, 0.9):
        h = 1e-6
        fp, fm = ocvirk_force(eps + h, MU, OMEGA, R_S, L_S, C_S), ocvirk_force(eps - h, MU, OMEGA, R_S, L_S, C_S)
        f = ocvirk_force(eps, MU, OMEGA, R_S, L_S, C_S)
        assert f[2] == pytest.approx((fp[0] - fm[0]) / (2 * h), rel=1e-6)
        assert f[3] == pytest.approx((fp[1] - fm[1]) / (2 * h), rel=1e-6)
        tp, tm = ocvirk_torque(eps + h, MU, OMEGA, R_S, L_S, C_S), ocvirk_torque(eps - h, MU, OMEGA, R_S, L_S, C_S)
        assert ocvirk_torque(eps, MU, OMEGA, R_S, L_S, C_S)[1] == pytest.approx((tp[0] - tm[0]) / (2 * h), rel=1e-6)


# --- dry part ------------------------------------------------------------------------------
@pytest.mark.parametrize("l, q_agree, gap_at_1N", [
    (3.8e-3, 3.5, (0.05, 0.10)),   # one land of the reference cage (lands = 2)
    (7.6e-3, 13.0, (0.10, 0.20)),  # the reference model's single journal (lands = 1)
])
def test_lundberg_vs_palmgren_bronze_on_steel(l, q_agree, gap_at_1N):
    # Palmgren delta[mm] = 3.84e-5 Q^0.9 / l^0.8 (steel; Harris & Kotzalas, Essential
    # Concepts of Bearing Technology, 5th ed., ch. 6) against Lundberg's logarithmic law
    # (docs/model.md §8), line lengths from docs/model.md §2, bronze on steel, Palmgren's load scaled
    # by E'/E'_steel (Lundberg depends on Q/E' only). Deflections at equal load agree within
    # 5 % from q_agree to 5 kN (-4.7 % .. +3.2 % at 3.8 mm); below, the logarithm grows as
    # Q -> 0 (at 1 N: 8.7 % for 3.8 mm, 16 % for 7.6 mm; Palmgren's power law is an empirical
    # fit for loaded contacts). Such loads are interferences under ~100 nm, where the dry
    # force is < 1 % of the cage-land force (next test). As a Newton start (load at equal
    # deflection) Palmgren is within 20 % over 1 N .. 5 kN.
    from bearingsim.dynamics.journal.dry import PALMGREN_COEFFICIENT, PALMGREN_E_EFF_STEEL

    scale = PALMGREN_E_EFF_STEEL / E_BRONZE_STEEL
    palmgren = lambda q: PALMGREN_COEFFICIENT * (q * scale) ** 0.9 / (l * 1e3) ** 0.8 * 1e-3  # m
    for q in np.geomspace(q_agree, 5000.0, 40):
        assert abs(lundberg_deflection(q, l, E_BRONZE_STEEL) / palmgren(q) - 1) < 0.05, q
    assert gap_at_1N[0] < abs(lundberg_deflection(1.0, l, E_BRONZE_STEEL) / palmgren(1.0) - 1) < gap_at_1N[1]
    for q in np.geomspace(1.0, 5000.0, 40):
        q_start = palmgren_load(lundberg_deflection(q, l, E_BRONZE_STEEL), l, E_BRONZE_STEEL)
        assert abs(q_start / q - 1) < 0.20, q


def test_dry_loads_below_palmgrens_range_are_negligible_in_the_blend():
    # Reference cage land (docs/model.md §2: R = 83 mm, one journal of L = 7.6 mm, radial guide
    # clearance C = 0.29 mm; NATO O-156 at 100 degC, 4.9 mPa s (dynamics/data/nato-o156.toml);
    # cage at ~140 rad/s), eps0 = 0.05. Where Lundberg's load is under 13 N (interference
    # under 100 nm, the first 0.7 % of the eps0 band) the blend's dry part (1 - f_F) Q is under
    # 1 % of the total force (measured: <= 0.65 %), so even the 16 % gap of the two laws there
    # moves the force by < 0.2 %; and the model uses Lundberg, Palmgren only starts Newton.
    R, L, C, eps0, mu, omega = 0.083, 7.6e-3, 0.29e-3, 0.05, 4.9e-3, 140.0
    for delta in np.linspace(1e-10, 95e-9, 50):
        q_dry = lundberg_load(delta, L, E_BRONZE_STEEL)[0]
        assert q_dry <= 13.0
        eps = 1.0 + delta / C
        f_f = hybrid_weights(eps, eps0)[0]
        f_n_film = ocvirk_force(eps / (1 + eps0), mu, omega, R, L, C * (1 + eps0))[0]
        total = f_f * f_n_film + (1 - f_f) * q_dry
        assert (1 - f_f) * q_dry < 1e-2 * total


def test_palmgren_formula_in_its_own_units():
    # Q = 1000 N, l = 10 mm, steel: delta = 3.84e-5 * 1000^0.9 / 10^0.8 mm = 3.050e-3 mm
    # (hand evaluation of Palmgren's formula as quoted in docs/model.md §8).
    from bearingsim.dynamics.journal.dry import PALMGREN_E_EFF_STEEL

    q = palmgren_load(3.84e-5 * 1000**0.9 / 10**0.8 * 1e-3, 10e-3, PALMGREN_E_EFF_STEEL)
    assert q == pytest.approx(1000.0, rel=1e-12)


def test_lundberg_newton_inverts_and_differentiates():
    l = 3.8e-3
    for q in np.geomspace(1e-3, 2e5, 30):
        delta = lundberg_deflection(q, l, E_BRONZE_STEEL)
        q_solved, stiffness = lundberg_load(delta, l, E_BRONZE_STEEL)
        assert q_solved == pytest.approx(q, rel=1e-11)
        assert stiffness == pytest.approx(1 / lundberg_compliance(q, l, E_BRONZE_STEEL), rel=1e-9)
        h = 1e-6 * delta
        fd = (lundberg_load(delta + h, l, E_BRONZE_STEEL)[0] - lundberg_load(delta - h, l, E_BRONZE_STEEL)[0]) / (2 * h)
        assert stiffness == pytest.approx(fd, rel=1e-5)
    assert lundberg_load(0.0, l, E_BRONZE_STEEL) == (0.0, 0.0)
    assert lundberg_load(-1e-6, l, E_BRONZE_STEEL) == (0.0, 0.0)


def test_lundberg_load_keeps_rising_past_the_curve_maximum():
    l = 3.8e-3
    deltas = np.linspace(1e-5, 5e-3, 200)  # up to 5 mm of interference: a crashed run
    loads = np.array([lundberg_load(d, l, E_BRONZE_STEEL)[0] for d in deltas])
    assert np.all(np.diff(loads) > 0) and np.all(np.isfinite(loads))


# --- hybrid blend --------------------------------------------------------------------------
def test_hybrid_weight_limits():
    eps0 = 0.05
    assert hybrid_weights(1.0, eps0) == (1.0, 0.0, 1.0, 0.0)
    assert hybrid_weights(1.0 + eps0, eps0) == (0.0, 0.0, 0.0, 0.0)
    f_f, df_f, f_c, df_c = hybrid_weights(1.0 + 1e-12, eps0)
    assert f_f == pytest.approx(1.0, abs=1e-9) and f_c == pytest.approx(1.0, abs=1e-9)
    assert df_f == pytest.approx(-2.0 / eps0, rel=1e-6)  # d/dchi exp(2chi/(chi-1)) = -2 at 0
    assert df_c == pytest.approx(-1.0 / eps0)
    f_f, df_f, f_c, _ = hybrid_weights(1.0 + eps0 * (1 - 1e-3), eps0)
    assert f_f < 1e-300 and abs(df_f) < 1e-290  # flat: exp(-2/(1-chi)) ~ exp(-2000)
    assert f_c == pytest.approx(1e-3)


def sample(p, eps_grid, **kw):
    return np.array([journal_at(e, p, **kw) for e in eps_grid])


@pytest.mark.parametrize("omega_race", [0.0, -30.0])
def test_force_and_torque_continuous_across_blend(omega_race):
    # dense sampling: a jump would not shrink when the grid is refined
    p = params(length=7.6e-3, radius=0.083, clearance=0.29e-3, viscosity=5e-3)
    jumps = []
    for n in (3001, 12001):
        out = sample(p, np.linspace(0.97, 1.08, n), omega_cage=140.0, omega_race=omega_race, velocity=(0.1, -0.2))
        jumps.append([np.max(np.abs(np.diff(out[:, k]))) for k in (0, 1, 3)])
    jumps = np.array(jumps)
    assert np.all(jumps[1] < 0.6 * jumps[0])  # Lipschitz: 0.25, sqrt cusp: 0.5, jump: 1
    for eps_star in (1.0, 1.05):
        for eta in (1e-6, 1e-9):
            below = journal_at(eps_star - eta, p, omega_cage=140.0, omega_race=omega_race)
            above = journal_at(eps_star + eta, p, omega_cage=140.0, omega_race=omega_race)
            scale = np.abs(below[[0, 1, 3]]) + 1.0
            assert np.all(np.abs(above[[0, 1, 3]] - below[[0, 1, 3]]) < 3 * math.sqrt(eta) * scale)


def test_slopes_finite_at_blend_edges():
    # Issue "contact kernels": force and torque derivatives finite at eps = 1 and 1 + eps0.
    p1 = params(length=7.6e-3, radius=0.083, clearance=0.29e-3, viscosity=5e-3)
    for eps in (1.0 - 1e-9, 1.0 + 1e-9, 1.05 - 1e-9, 1.05 + 1e-9):
        out = journal_at(eps, p1, omega_cage=140.0)
        assert np.all(np.isfinite(out))
        assert np.max(np.abs(out[J_OUT_DF_DPOS:J_OUT_DF_DPOS + 4])) < 1e12  # N/m: a wall, but finite
        assert abs(out[J_OUT_DT_DPOS]) < 1e8  # N m / m
    # Approaching 1 + eps0 from below without dry friction (torque = f_C T^hyd only). With the
    # film torque clipped at eps_h = 0.999 (default) the slope levels off at a finite value;
    # with the clip pushed to 1 - 1e-12 (eq. 31 as written) it grows like
    # (1 + eps0 - eps)^(-1/2): x10 for 100x closer -- infinite in the limit.
    film_only = dict(length=7.6e-3, radius=0.083, clearance=0.29e-3, viscosity=5e-3, friction_coefficient=0.0)
    slope = lambda eta, **kw: journal_at(1.05 - eta, params(**film_only, **kw), omega_cage=140.0)[J_OUT_DT_DPOS]
    assert slope(1e-8) / slope(1e-6) == pytest.approx(1.0, rel=1e-9)
    assert slope(1e-8, eps_clip=1 - 1e-12) / slope(1e-6, eps_clip=1 - 1e-12) == pytest.approx(10.0, rel=0.02)
    # FD slope of the torque agrees with the kernel's, across the clip point too
    for eps in (1.02, 1.0485, 1.0495):
        h = 1e-9
        fd = (journal_at(eps + h, params(**film_only), omega_cage=140.0)[J_OUT_TORQUE]
              - journal_at(eps - h, params(**film_only), omega_cage=140.0)[J_OUT_TORQUE]) / (2 * h * 0.29e-3)
        assert journal_at(eps, params(**film_only), omega_cage=140.0)[J_OUT_DT_DPOS] == pytest.approx(fd, rel=1e-4)


def test_torque_clip_only_acts_in_the_last_two_percent_of_the_band():
    # eq. 31 (clip at 1 - 1e-12) and the default (clip 0.999) agree exactly up to
    # eps = 0.999 (1 + eps0) = 1 + 0.979 eps0, and differ by less than f_C T^hyd beyond.
    film_only = dict(length=7.6e-3, radius=0.083, clearance=0.29e-3, viscosity=5e-3, friction_coefficient=0.0)
    default, paper = params(**film_only), params(**film_only, eps_clip=1 - 1e-12)
    for eps in np.linspace(0.5, 1.05 * 0.999 - 1e-9, 200):
        assert journal_at(eps, default, omega_cage=140.0)[J_OUT_TORQUE] == journal_at(eps, paper, omega_cage=140.0)[J_OUT_TORQUE]
    band_start = abs(journal_at(1.0, paper, omega_cage=140.0)[J_OUT_TORQUE])
    for eps in np.linspace(1.05 * 0.999, 1.05 - 1e-12, 200):
        d = abs(journal_at(eps, default, omega_cage=140.0)[J_OUT_TORQUE] - journal_at(eps, paper, omega_cage=140.0)[J_OUT_TORQUE])
        assert d <= 0.15 * band_start


def test_dry_region_is_lundberg_with_full_slip():
    p = params(length=7.6e-3, radius=0.083, clearance=0.29e-3, viscosity=5e-3, friction_coefficient=0.15, lands=2)
    eps = 1.2
    out = journal_at(eps, p, omega_cage=140.0, azimuth=0.7)
    q_land, _ = lundberg_load(0.2 * 0.29e-3, 3.8e-3, E_BRONZE_STEEL)
    er = np.array([math.cos(0.7), math.sin(0.7)])
    et = np.array([-er[1], er[0]])
    assert out[:2] @ er == pytest.approx(-2 * q_land, rel=1e-12)
    assert out[:2] @ et == pytest.approx(-0.15 * 2 * q_land, rel=1e-9)  # tanh(11.6/1e-3) = 1
    assert out[J_OUT_TORQUE] == pytest.approx(-0.15 * 2 * q_land * 0.083, rel=1e-9)
    assert out[J_OUT_METAL_FORCE] == pytest.approx(2 * q_land, rel=1e-12)
    assert out[J_OUT_FRICTION_POWER] == pytest.approx(0.15 * 2 * q_land * 140.0 * 0.083, rel=1e-9)
    assert out[J_OUT_CONTACT_AZIMUTH] == pytest.approx(0.7)


# --- directions and invariants -------------------------------------------------------------
def test_directions_follow_rotation_and_guidance():
    p = params()
    fwd, back = journal_at(0.5, p, omega_cage=OMEGA), journal_at(0.5, p, omega_cage=-OMEGA)
    assert fwd[0] == pytest.approx(back[0]) and fwd[1] == pytest.approx(-back[1])  # F_t follows omega
    assert fwd[J_OUT_TORQUE] < 0 < back[J_OUT_TORQUE]  # opposes cage rotation relative to race
    # both surfaces turning together: entrainment doubles, shear vanishes
    together = journal_at(0.5, p, omega_cage=OMEGA, omega_race=OMEGA)
    assert together[1] == pytest.approx(2 * fwd[1]) and together[J_OUT_TORQUE] == 0.0
    # inner-race guidance: the land touches on the far side, friction still opposes sliding
    inner = params(guidance="inner")
    out = journal_at(1.2, inner, omega_cage=OMEGA, azimuth=0.3)
    et = np.array([-math.sin(0.3), math.cos(0.3)])
    assert out[:2] @ et > 0 and out[J_OUT_TORQUE] < 0
    assert out[J_OUT_CONTACT_AZIMUTH] == pytest.approx(0.3 - math.pi)


def test_rotational_invariance():
    rng = np.random.default_rng(3)
    p = params(length=7.6e-3, radius=0.083, clearance=0.29e-3, viscosity=5e-3)
    for eps in (0.4, 1.02, 1.3):
        offset = eps * 0.29e-3 * np.array([0.6, 0.8])
        vel = rng.normal(size=2) * 0.05
        a = rng.uniform(0, 2 * math.pi)
        rot = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
        o1 = unpack_journal(cage_race_journal(offset, vel, 140.0, 0.0, p))
        o2 = unpack_journal(cage_race_journal(rot @ offset, rot @ vel, 140.0, 0.0, p))
        scale = np.abs(o1["force"]).max()
        np.testing.assert_allclose(o2["force"][:2], rot @ o1["force"][:2], atol=1e-12 * scale)
        assert o2["torque"] == pytest.approx(o1["torque"], rel=1e-10)
        jscale = np.abs(o1["dforce_dposition"]).max()
        np.testing.assert_allclose(o2["dforce_dposition"], rot @ o1["dforce_dposition"] @ rot.T, atol=1e-9 * jscale)


def random_states(rng, n):
    eps_values = np.concatenate([rng.uniform(0.0, 0.98, n), rng.uniform(1.002, 1.048, n), rng.uniform(1.06, 1.5, n)])
    for eps in eps_values:
        a = rng.uniform(0, 2 * math.pi)
        yield (eps * 0.29e-3 * np.array([math.cos(a), math.sin(a)]), rng.normal(size=2) * 0.05,
               rng.uniform(-200, 200), rng.uniform(-50, 50))


@pytest.mark.parametrize("mode", ["hybrid", "dry", "hydrodynamic"])
@pytest.mark.parametrize("guidance", ["outer", "inner"])
def test_tangents_against_finite_differences(mode, guidance):
    rng = np.random.default_rng(7)
    p = params(length=7.6e-3, radius=0.083, clearance=0.29e-3, viscosity=5e-3, mode=mode, guidance=guidance,
               regularisation_speed=0.05, lands=2)
    for offset, vel, wc, wr in random_states(rng, 6):
        out = cage_race_journal(offset, vel, wc, wr, p)
        f = lambda o=offset, v=vel, a=wc, b=wr: cage_race_journal(o, v, a, b, p)[[0, 1, 3]]
        hx, hv, hw = 1e-9 * 0.29e-3, 1e-7, 1e-5
        cols = []
        for j in range(2):
            d = np.zeros(2)
            d[j] = hx
            cols.append((f(o=offset + d) - f(o=offset - d)) / (2 * hx))
        for j in range(2):
            d = np.zeros(2)
            d[j] = hv
            cols.append((f(v=vel + d) - f(v=vel - d)) / (2 * hv))
        cols.append((f(a=wc + hw) - f(a=wc - hw)) / (2 * hw))
        cols.append((f(b=wr + hw) - f(b=wr - hw)) / (2 * hw))
        fd = np.array(cols).T  # rows Fx, Fy, T; columns x, y, vx, vy, wc, wr
        an = np.array([
            [*out[J_OUT_DF_DPOS:J_OUT_DF_DPOS + 2], *out[J_OUT_DF_DVEL:J_OUT_DF_DVEL + 2],
             out[J_OUT_DF_DOMEGA_CAGE], out[J_OUT_DF_DOMEGA_RACE]],
            [*out[J_OUT_DF_DPOS + 2:J_OUT_DF_DPOS + 4], *out[J_OUT_DF_DVEL + 2:J_OUT_DF_DVEL + 4],
             out[J_OUT_DF_DOMEGA_CAGE + 1], out[J_OUT_DF_DOMEGA_RACE + 1]],
            [*out[J_OUT_DT_DPOS:J_OUT_DT_DPOS + 2], *out[J_OUT_DT_DVEL:J_OUT_DT_DVEL + 2],
             out[J_OUT_DT_DOMEGA_CAGE], out[J_OUT_DT_DOMEGA_RACE]],
        ])
        for j in range(6):  # compare column by column at each column's own scale
            scale = np.abs(an[:, j]).max() + np.abs(fd[:, j]).max() + 1e-9
            assert np.abs(an[:, j] - fd[:, j]).max() < 2e-5 * scale, (mode, out[J_OUT_EPS], j, an[:, j], fd[:, j])


def test_tangent_at_the_concentric_position():
    # at e = 0 the direction e_r is undefined but the film stiffness is not:
    # F ~ (F_t/e) e_z x offset, a pure cross-coupling (rotation) matrix
    p = params()
    out = cage_race_journal(np.zeros(2), np.zeros(2), OMEGA, 0.0, p)
    h = 1e-9 * C_S
    fd = np.array([(cage_race_journal(np.array(d), np.zeros(2), OMEGA, 0.0, p)[:2]
                    - cage_race_journal(-np.array(d), np.zeros(2), OMEGA, 0.0, p)[:2]) / (2 * h)
                   for d in ((h, 0.0), (0.0, h))]).T
    np.testing.assert_allclose(out[J_OUT_DF_DPOS:J_OUT_DF_DPOS + 4].reshape(2, 2), fd,
                               rtol=1e-6, atol=1e-7 * np.abs(fd).max())
    assert out[0] == 0.0 and out[1] == 0.0  # no film force at the centre ...
    assert out[J_OUT_TORQUE] < 0.0  # ... but Petroff's drag


def test_modes_dry_and_none():
    dry = params(mode="dry")
    assert np.all(journal_at(0.99, dry)[[0, 1, 3]] == 0.0)
    assert journal_at(1.01, dry)[0] < 0
    assert np.all(journal_at(1.5, params(mode="none"))[[0, 1, 3]] == 0.0)
    clipped = journal_at(1.5, params(mode="hydrodynamic", eps_clip=0.99))
    f_n, _, _, _ = ocvirk_force(0.99, MU, OMEGA, R_S, L_S, C_S)
    assert -clipped[0] == pytest.approx(f_n)


def test_kernels_equal_their_python_twins():
    rng = np.random.default_rng(11)
    p = params(length=7.6e-3, radius=0.083, clearance=0.29e-3, viscosity=5e-3, regularisation_speed=0.05)
    for offset, vel, wc, wr in random_states(rng, 5):
        np.testing.assert_allclose(cage_race_journal.py_func(offset, vel, wc, wr, p),
                                   cage_race_journal(offset, vel, wc, wr, p), rtol=1e-12, atol=1e-300)
        e = math.hypot(*offset)
        np.testing.assert_allclose(journal_scalars.py_func(e, 0.3, wc + wr, wc - wr, p),
                                   journal_scalars(e, 0.3, wc + wr, wc - wr, p), rtol=1e-12)
    for eps in rng.uniform(0, 0.99, 10):
        np.testing.assert_allclose(ocvirk_force.py_func(eps, MU, OMEGA, R_S, L_S, C_S),
                                   ocvirk_force(eps, MU, OMEGA, R_S, L_S, C_S), rtol=1e-13)
        np.testing.assert_allclose(ocvirk_torque.py_func(eps, MU, OMEGA, R_S, L_S, C_S),
                                   ocvirk_torque(eps, MU, OMEGA, R_S, L_S, C_S), rtol=1e-13)
    for eps in rng.uniform(0.9, 1.1, 10):
        np.testing.assert_allclose(hybrid_weights.py_func(eps, 0.05), hybrid_weights(eps, 0.05), rtol=1e-13)
    for delta in rng.uniform(0, 1e-4, 10):
        np.testing.assert_allclose(lundberg_load.py_func(delta, 3.8e-3, E_BRONZE_STEEL),
                                   lundberg_load(delta, 3.8e-3, E_BRONZE_STEEL), rtol=1e-13)


# --- set-up ----------------------------------------------------------------------------------
def reference_geometry():
    bearing = BearingGeometry(0.01905, 22, 0.1584, 0.1573, 0.009753, 0.009906,
                              inner_shoulder_diameter=0.150, outer_shoulder_diameter=0.166,
                              inner_bore_diameter=0.130, outer_outside_diameter=0.196, width=0.034)
    return bearing, CageGeometry(0.158, 0.02023, 0.00742, 0.0254, "outer")


def test_reference_cage_parameters():
    # docs/model.md §2: R = 83 mm, C = 0.29 mm, L ≈ 7.6 mm (two lands of ≈ 3.80 mm)
    bearing, cage = reference_geometry()
    p = journal_parameters_for_cage(bearing, cage, BRONZE, STEEL, viscosity=5e-3, friction_coefficient=0.1)
    assert p.radius == pytest.approx(0.083) and p.clearance == pytest.approx(0.29e-3)
    assert p.length == pytest.approx(7.6e-3, abs=0.05e-3)


@pytest.mark.parametrize("bad, word", [
    (dict(clearance=0.0), "clearance"), (dict(mode="wet"), "mode"), (dict(lands=1.5), "lands"),
    (dict(viscosity=-1.0), "viscosity"), (dict(guidance="ball"), "guidance"), (dict(eps_clip=1.0), "eps_clip"),
])
def test_parameter_errors_name_the_key(bad, word):
    with pytest.raises(ValueError, match=word):
        params(**bad)
