"""Verification problems with closed-form answers (used by tests and the benchmark).

- Cantilever with an end shear load against Timoshenko beam theory: tip deflection
  w = P L^3/(3 E I) + P L/(kappa G A), cross-section rotation phi = P L^2/(2 E I)
  (Timoshenko & Gere, "Mechanics of Materials"; Timoshenko & Goodier, "Theory of
  Elasticity", 3rd ed., §21 for the elasticity solution), shear coefficient of a
  rectangle kappa = 10 (1 + nu)/(12 + 11 nu) (Cowper, J. Appl. Mech. 33:335, 1966, Table 1).
- Thick-walled open tube under internal pressure p (Lamé; Timoshenko & Goodier §28):
  u_r(r) = [(1 - nu) A r + (1 + nu) B / r]/E, A = p a^2/(b^2 - a^2), B = A b^2,
  with sigma_z = 0 (free ends), an exact 3-D solution. Solved in 3-D (`solve`) and as
  Fourier mode 0 of the axisymmetric model (`solve_axisymmetric`).
- Tube cantilever with an end shear load (Fourier mode 1 of the axisymmetric model) against
  Timoshenko beam theory, shear coefficient of a hollow circle
  kappa = 6 (1 + nu)(1 + m^2)^2 / [(7 + 6 nu)(1 + m^2)^2 + (20 + 12 nu) m^2], m = a/b
  (Cowper 1966, Table 1).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

import math

from .elasticity import ElasticModel
from .loads import RegionMoments, distributed_load_matrix, rigid_fit_operator
from .solvers import SPDFactorization


def timoshenko_tip(P: float, L: float, E: float, G: float, I: float, A: float, kappa: float) -> tuple[float, float]:
    """Tip of a cantilever under a tip shear load P: (deflection [m], cross-section rotation
    [rad]) of Timoshenko's beam, PL^3/(3EI) + PL/(kappa G A) and PL^2/(2EI)."""
    return P * L**3 / (3 * E * I) + P * L / (kappa * G * A), P * L**2 / (2 * E * I)


@dataclass(frozen=True)
class Cantilever:
    length: float = 1.0  # m
    width: float = 0.1  # m
    height: float = 0.1  # m
    youngs_modulus: float = 210e9  # Pa
    poisson_ratio: float = 0.3
    load: float = 1.0e4  # N, along +z at the tip

    def timoshenko(self) -> tuple[float, float]:
        """(tip deflection w [m], tip cross-section rotation phi [rad])."""
        L, b, h, P = self.length, self.width, self.height, self.load
        E, nu = self.youngs_modulus, self.poisson_ratio
        I, A, G = b * h**3 / 12.0, b * h, E / (2.0 * (1.0 + nu))
        kappa = 10.0 * (1.0 + nu) / (12.0 + 11.0 * nu)
        return timoshenko_tip(P, L, E, G, I, A, kappa)

    def solve(self, mesh_size: float, order: int) -> tuple[float, float, int]:
        """FE (tip deflection [m], tip rotation [rad], dofs): root clamped, uniform shear
        traction on the tip, tip face rigid-fitted about its centroid."""
        from skfem import FacetBasis

        from ..meshes.verification import cantilever_mesh

        mesh = cantilever_mesh(self.length, self.width, self.height, mesh_size).to_skfem()
        model = ElasticModel.build(mesh, order, {"beam": (self.youngs_modulus, self.poisson_ratio)})
        K, free = model.stiffness_upper(model.boundary_dofs("root"))
        tip = RegionMoments.of(
            FacetBasis(mesh, model.basis.elem, facets=mesh.boundaries["tip"], intorder=order + 2),
            centre=(self.length, 0.0, 0.0),
        )
        f = distributed_load_matrix(tip)[:, 2] * self.load
        u = np.zeros(model.n_dofs)
        u[free] = SPDFactorization(K).solve(f[free])
        q = rigid_fit_operator(tip) @ u
        # a rotation theta_y about +y moves +x points towards -z: phi = -theta_y
        return float(q[2]), float(-q[4]), model.n_dofs


@dataclass(frozen=True)
class LameTube:
    inner_radius: float = 0.05  # m
    outer_radius: float = 0.10  # m
    half_length: float = 0.05  # m
    youngs_modulus: float = 210e9  # Pa
    poisson_ratio: float = 0.3
    pressure: float = 100e6  # Pa

    def radial_displacement(self, r: float) -> float:
        a, b, p, E, nu = self.inner_radius, self.outer_radius, self.pressure, self.youngs_modulus, self.poisson_ratio
        A = p * a**2 / (b**2 - a**2)
        return ((1 - nu) * A * r + (1 + nu) * A * b**2 / r) / E

    def solve(self, mesh_size: float, order: int) -> tuple[float, float, int]:
        """FE surface-mean radial displacement at the bore and outside [m], and dofs."""
        from skfem import FacetBasis, LinearForm

        from ..meshes.verification import quarter_tube_mesh

        mesh = quarter_tube_mesh(self.inner_radius, self.outer_radius, self.half_length, mesh_size).to_skfem()
        model = ElasticModel.build(mesh, order, {"tube": (self.youngs_modulus, self.poisson_ratio)})
        fixed = np.concatenate([model.boundary_dofs(g, (c,)) for g, c in (("sym_x", 0), ("sym_y", 1), ("sym_z", 2))])
        K, free = model.stiffness_upper(fixed)

        def radial_moments(group: str) -> np.ndarray:
            """(3N,) vector m with m . u = int u . e_r over the group's surface."""
            fb = FacetBasis(mesh, model.basis.elem, facets=mesh.boundaries[group], intorder=order + 2)
            comps = [LinearForm(lambda v, w, c=c: w.x[c] / np.hypot(w.x[0], w.x[1]) * v).assemble(fb)
                     for c in (0, 1)]
            return np.column_stack([comps[0], comps[1], np.zeros_like(comps[0])]).ravel()

        bore, outside = radial_moments("bore"), radial_moments("outside")
        # pressure on the bore pushes along +e_r: f = p int e_r . v
        u = np.zeros(model.n_dofs)
        u[free] = SPDFactorization(K).solve((self.pressure * bore)[free])
        area_bore = 0.5 * np.pi * self.inner_radius * self.half_length
        area_out = 0.5 * np.pi * self.outer_radius * self.half_length
        return float(bore @ u / area_bore), float(outside @ u / area_out), model.n_dofs

    def solve_axisymmetric(self, mesh_size: float, order: int) -> tuple[float, float, int]:
        """Mode 0 of the axisymmetric model on the section [a, b] x [0, H], U_z = 0 at z = 0:
        surface-mean radial displacement at the bore and outside [m], and dofs."""
        from skfem import FacetBasis, LinearForm

        from .axisymmetric import HarmonicModel

        a, b, H = self.inner_radius, self.outer_radius, self.half_length
        mesh = _section(a, b, 0.0, H, mesh_size, {
            "bore": lambda k: k[0] == "r" and math.isclose(k[1], a, abs_tol=1e-6),
            "outside": lambda k: k[0] == "r" and math.isclose(k[1], b, abs_tol=1e-6),
            "sym_z": lambda k: k[0] == "z" and math.isclose(k[1], 0.0, abs_tol=1e-6)})
        model = HarmonicModel.build(mesh, order, {"tube": (self.youngs_modulus, self.poisson_ratio)})
        K, reduction = model.stiffness_upper(0, model.boundary_dofs("sym_z", (2,)))

        def radial_moments(group: str) -> np.ndarray:
            """(3N,) m with m . U = int U_r r dz over the line (the surface integral / 2 pi)."""
            fb = FacetBasis(mesh, model.basis.elem, facets=mesh.boundaries[group], intorder=order + 2)
            m = np.zeros((model.basis.N, 3))
            m[:, 0] = LinearForm(lambda v, w: w.x[0] * v).assemble(fb)
            return m.ravel()

        bore, outside = radial_moments("bore"), radial_moments("outside")
        f = 2.0 * np.pi * self.pressure * bore  # p e_r on the bore, round the axis
        u = reduction.expand(SPDFactorization(K).solve(reduction.restrict(f)))
        return float(bore @ u / (a * H)), float(outside @ u / (b * H)), model.n_dofs


@dataclass(frozen=True)
class TubeCantilever:
    length: float = 1.0  # m
    inner_radius: float = 0.04  # m
    outer_radius: float = 0.05  # m
    youngs_modulus: float = 210e9  # Pa
    poisson_ratio: float = 0.3
    load: float = 1.0e4  # N, along +x at the tip

    def timoshenko(self) -> tuple[float, float]:
        """(tip deflection w [m], tip cross-section rotation phi [rad])."""
        a, b, L, P = self.inner_radius, self.outer_radius, self.length, self.load
        E, nu = self.youngs_modulus, self.poisson_ratio
        I, A, G, m2 = math.pi * (b**4 - a**4) / 4.0, math.pi * (b**2 - a**2), E / (2.0 * (1.0 + nu)), (a / b) ** 2
        kappa = 6.0 * (1.0 + nu) * (1.0 + m2) ** 2 / ((7.0 + 6.0 * nu) * (1.0 + m2) ** 2 + (20.0 + 12.0 * nu) * m2)
        return timoshenko_tip(P, L, E, G, I, A, kappa)

    def solve(self, mesh_size: float, order: int) -> tuple[float, float, int]:
        """Mode 1 of the axisymmetric model: root z = -L clamped, M.43 shear traction on the
        tip face z = 0 (its centroid is the origin), tip face rigid-fitted (M.44):
        (tip deflection [m], tip rotation [rad], dofs)."""
        from skfem import FacetBasis

        from .axisymmetric import AxisymmetricRegion, HarmonicModel, mode1_load, rigid_fit_rows

        a, b, L = self.inner_radius, self.outer_radius, self.length
        mesh = _section(a, b, -L, 0.0, mesh_size, {
            "root": lambda k: k[0] == "z" and math.isclose(k[1], -L, abs_tol=1e-6),
            "tip": lambda k: k[0] == "z" and math.isclose(k[1], 0.0, abs_tol=1e-6)})
        model = HarmonicModel.build(mesh, order, {"tube": (self.youngs_modulus, self.poisson_ratio)})
        K, reduction = model.stiffness_upper(1, model.boundary_dofs("root"))
        tip = AxisymmetricRegion.of(FacetBasis(mesh, model.basis.elem, facets=mesh.boundaries["tip"],
                                               intorder=order + 3))
        u = reduction.expand(SPDFactorization(K).solve(reduction.restrict(mode1_load(tip, self.load, 0.0))))
        q = rigid_fit_rows(tip)[0] @ u
        # a rotation theta_y about +y moves points at +z towards +x: phi = theta_y
        return float(q[0]), float(q[4]), model.n_dofs


def _section(r0: float, r1: float, z0: float, z1: float, mesh_size: float, lines: dict):
    """skfem MeshTri of the rectangle [r0, r1] x [z0, z1] (part "tube"), uniform triangles."""
    from ..meshes.section import mesh_rectangles

    return mesh_rectangles({"tube": [(r0, r1, z0, z1)]}, lines, mesh_size, mesh_size, 1.0, 1e-6).to_skfem()
