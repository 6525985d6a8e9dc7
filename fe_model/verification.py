"""Verification problems with closed-form answers (used by tests and the benchmark).

- Cantilever with an end shear load against Timoshenko beam theory: tip deflection
  w = P L^3/(3 E I) + P L/(kappa G A), cross-section rotation phi = P L^2/(2 E I)
  (Timoshenko & Gere, "Mechanics of Materials"; Timoshenko & Goodier, "Theory of
  Elasticity", 3rd ed., §21 for the elasticity solution), shear coefficient of a
  rectangle kappa = 10 (1 + nu)/(12 + 11 nu) (Cowper, J. Appl. Mech. 33:335, 1966, Table 1).
- Thick-walled open tube under internal pressure p (Lamé; Timoshenko & Goodier §28):
  u_r(r) = [(1 - nu) A r + (1 + nu) B / r]/E, A = p a^2/(b^2 - a^2), B = A b^2,
  with sigma_z = 0 (free ends), an exact 3-D solution.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from bearingsim.fe_model.elasticity import ElasticModel
from bearingsim.fe_model.loads import RegionMoments, distributed_load_matrix, rigid_fit_operator
from bearingsim.fe_model.solvers import SPDFactorization


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
        return P * L**3 / (3 * E * I) + P * L / (kappa * G * A), P * L**2 / (2 * E * I)

    def solve(self, mesh_size: float, order: int) -> tuple[float, float, int]:
        """FE (tip deflection [m], tip rotation [rad], dofs): root clamped, uniform shear
        traction on the tip, tip face rigid-fitted about its centroid."""
        from skfem import FacetBasis

        from bearingsim.meshes.verification import cantilever_mesh

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

        from bearingsim.meshes.verification import quarter_tube_mesh

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
