"""Axisymmetric elasticity under Fourier modes 0 and 1: the stage-1 model (docs/model.md §3).

The assembly is a body of revolution about z with axisymmetric materials and clamp, and every
perturbation load of §3 is a single Fourier mode round the axis: F_z is mode 0 and F_x, F_y,
M_x, M_y are mode 1 (the RBE3 traction t = F/A + a x (x - x_bar) of M.43 on a surface of
revolution has components ~cos(theta) and ~sin(theta), or none in theta for F_z). So the 3-D
problem splits exactly into 2-D problems on the meridian section (r, z): with

    u_r = U_r(r, z) cos n theta,   u_theta = U_theta(r, z) sin n theta,   u_z = U_z(r, z) cos n theta

mode 1 carries (F_x, M_y), mode 0 carries F_z, and F_y, M_x are mode 1 turned by 90 degrees
(E. L. Wilson, "Structural analysis of axisymmetric solids", AIAA J. 3:2269, 1965). The
section is meshed with quadratic triangles graded to its corners, which is where the 3-D
tetrahedral mesh spent its degrees of freedom: the stresses are singular along the circular
edges but smooth round them, so resolving the singularity costs a few hundred triangles
instead of hundreds of thousands of tetrahedra. The load distribution (M.43) and the rigid
fit (M.44) are the same integrals as in `loads.py`, evaluated round the axis in closed form.

Units: SI. Global dof numbering: 3 * scalar dof + (0: U_r, 1: U_theta, 2: U_z).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from .elasticity import VectorFieldModel, full_from_upper, lame_fields, scalar_element
from .kernels import csr_from_triplets, harmonic_stiffness_upper, upper_triplet_indices
from .loads import EPS

# int_0^2pi cos^2(n theta) and sin^2(n theta) for the modes used
MODE_WEIGHTS = {0: (2.0 * math.pi, 0.0), 1: (math.pi, math.pi)}
AXIS_TOL = 1e-9  # m: nodes this close to the axis carry the regularity conditions


@dataclass
class Reduction:
    """Map between all dofs of a mode and the unknowns of its reduced system: `free` dofs
    kept (the others are zero), or a sparse `T` (dofs x unknowns) when some dofs are tied."""

    n_dofs: int
    free: np.ndarray
    T: sp.csr_matrix | None = None

    @property
    def size(self) -> int:
        return int(self.free.size) if self.T is None else int(self.T.shape[1])

    def restrict(self, f: np.ndarray) -> np.ndarray:
        """Load(s) on the unknowns: f[free] or T^T f."""
        return f[self.free] if self.T is None else self.T.T @ f

    def expand(self, x: np.ndarray) -> np.ndarray:
        """All dofs from the unknowns."""
        if self.T is not None:
            return self.T @ x
        out = np.zeros((self.n_dofs,) + x.shape[1:])
        out[self.free] = x
        return out


class HarmonicModel(VectorFieldModel):
    """A meshed meridian section ready to assemble: skfem MeshTri (x = r, y = z), scalar
    basis, Lamé parameters per element [Pa]; components U_r, U_theta, U_z of a Fourier mode."""

    @classmethod
    def build(cls, mesh, order: int, materials: dict[str, tuple[float, float]]) -> "HarmonicModel":
        """`materials` maps a subdomain name to (E [Pa], nu [-]); every element needs one."""
        from skfem import Basis

        lam, mu = lame_fields(mesh, materials, "part")
        if mesh.p[0].min() < -AXIS_TOL:
            raise ValueError("the section must lie in r >= 0 (x is the radius)")
        # the integrand is polynomial (degree 3 for P2) plus phi^2 / r, smooth off the axis: a
        # 4th-order rule (the Lamé tube converges to 1e-6, tests/test_fe_axisymmetric.py)
        basis = Basis(mesh, scalar_element(order, "tri"), intorder=2 * order)
        return cls(mesh, basis, lam, mu)

    def axis_nodes(self) -> np.ndarray:
        """Scalar dofs on the axis r = 0 (a solid shaft)."""
        return np.flatnonzero(np.abs(self.basis.doflocs[0]) <= AXIS_TOL)

    def stiffness_upper(self, mode: int, fixed: np.ndarray) -> tuple[sp.csr_matrix, Reduction]:
        """Upper triangle of the mode's stiffness on its unknowns, and the dof map.

        Besides `fixed` (clamped) dofs: mode 0 drops U_theta (torsion, not loaded) and U_r on
        the axis; mode 1 sets U_z = 0 and ties U_theta = -U_r on the axis (a single-valued,
        finite displacement at r = 0)."""
        if mode not in MODE_WEIGHTS:
            raise ValueError(f"Fourier mode {mode!r}: only 0 and 1 are implemented")
        c_cos, c_sin = MODE_WEIGHTS[mode]
        axis = self.axis_nodes()
        drop = [np.asarray(fixed, dtype=np.int64)]
        if mode == 0:
            drop += [3 * np.arange(self.basis.N) + 1, 3 * axis]
        else:
            drop += [3 * axis + 2]
        b = self.basis
        phi = np.ascontiguousarray(np.stack([np.asarray(f[0]) for f in b.basis], axis=2))
        grads = np.ascontiguousarray(np.stack([np.moveaxis(f[0].grad, 0, -1) for f in b.basis], axis=2))
        r = np.ascontiguousarray(b.mapping.F(b.X)[0])
        values = harmonic_stiffness_upper(phi, grads, r, np.ascontiguousarray(b.dx), self.lam, self.mu,
                                          float(mode), c_cos, c_sin)
        del phi, grads
        keep = np.ones(self.n_dofs, dtype=bool)
        keep[np.concatenate(drop)] = False
        tied = 3 * axis + 1 if (mode == 1 and axis.size) else np.empty(0, dtype=np.int64)
        if tied.size == 0:
            free_map = np.where(keep, np.cumsum(keep) - 1, -1)
            free = np.flatnonzero(keep)
            rows, cols = upper_triplet_indices(np.ascontiguousarray(free_map[self.vector_dofs()]))
            indptr, indices, data = csr_from_triplets(rows, cols, values.ravel(), free.size)
            K = sp.csr_matrix((data, indices, indptr), shape=(free.size, free.size))
            K.has_canonical_format = True
            return K, Reduction(self.n_dofs, free)
        # tie U_theta = -U_r on the axis: K_red = T^T K T on the full matrix
        everything = np.arange(self.n_dofs, dtype=np.int64)
        rows, cols = upper_triplet_indices(np.ascontiguousarray(everything[self.vector_dofs()]))
        indptr, indices, data = csr_from_triplets(rows, cols, values.ravel(), self.n_dofs)
        K_full = full_from_upper(sp.csr_matrix((data, indices, indptr), shape=(self.n_dofs, self.n_dofs)))
        keep[tied] = False
        unknown = np.where(keep, np.cumsum(keep) - 1, -1)
        free = np.flatnonzero(keep)
        tied = tied[unknown[tied - 1] >= 0]  # U_r clamped on the axis: U_theta is zero too
        T = sp.csr_matrix(
            (np.r_[np.ones(free.size), -np.ones(tied.size)],
             (np.r_[free, tied], np.r_[unknown[free], unknown[tied - 1]])),
            shape=(self.n_dofs, free.size))
        K = sp.triu(T.T @ K_full @ T).tocsr()
        K.sort_indices()
        return K, Reduction(self.n_dofs, free, T)


@dataclass(frozen=True)
class AxisymmetricRegion:
    """Integrals over a region of revolution (a set of section lines = a surface, or of parts
    = a volume) about the origin, with dmu = dl or dr dz in the section [SI]:
    m0 = int phi r dmu, mz = int phi z r dmu, mr = int phi r^2 dmu per scalar dof; the 3-D
    measure (area or volume) 2 pi int r dmu, first moment int z, and second moments
    int x^2 = int y^2 and int z^2 of the body of revolution."""

    m0: np.ndarray
    mz: np.ndarray
    mr: np.ndarray
    measure: float
    first_z: float
    second_xx: float
    second_zz: float

    @classmethod
    def of(cls, basis) -> "AxisymmetricRegion":
        """From a scalar skfem basis restricted to the region (Basis(elements=...) or
        FacetBasis(facets=...)) on the section mesh (x = r, y = z)."""
        from skfem import Functional, LinearForm

        m0 = LinearForm(lambda v, w: w.x[0] * v).assemble(basis)
        mz = LinearForm(lambda v, w: w.x[1] * w.x[0] * v).assemble(basis)
        mr = LinearForm(lambda v, w: w.x[0] ** 2 * v).assemble(basis)

        def integral(f) -> float:
            return float(Functional(f).assemble(basis))

        return cls(m0, mz, mr,
                   measure=2.0 * math.pi * integral(lambda w: w.x[0]),
                   first_z=2.0 * math.pi * integral(lambda w: w.x[1] * w.x[0]),
                   second_xx=math.pi * integral(lambda w: w.x[0] ** 3),
                   second_zz=2.0 * math.pi * integral(lambda w: w.x[1] ** 2 * w.x[0]))


def mode1_load(region: AxisymmetricRegion, force_x: float, moment_y: float) -> np.ndarray:
    """(3N,) mode-1 nodal loads of the M.43 traction with resultant F = (F_x, 0, 0) and moment
    M = (0, M_y, 0) about the origin. On the body, x_bar = (0, 0, z_bar), d = x_bar, and
    a = (0, a_y, 0) with a_y = (M_y - z_bar F_x)/J_yy, J_yy = int (x^2 + (z - z_bar)^2); the
    traction t = F/A + a x (x - x_bar) has t_r = (F_x/A + a_y z') cos, t_theta = -(...) sin,
    t_z = -a_y r cos, and f = int t . phi dA round the axis (a factor pi)."""
    A = region.measure
    z_bar = region.first_z / A
    J_yy = region.second_xx + region.second_zz - A * z_bar**2
    alpha, a_y = force_x / A, (moment_y - z_bar * force_x) / J_yy
    f = np.zeros((region.m0.size, 3))
    f[:, 0] = math.pi * (alpha * region.m0 + a_y * (region.mz - z_bar * region.m0))
    f[:, 1] = -f[:, 0]
    f[:, 2] = -math.pi * a_y * region.mr
    return f.ravel()


def mode0_load(region: AxisymmetricRegion, force_z: float) -> np.ndarray:
    """(3N,) mode-0 nodal loads of the M.43 traction with resultant (0, 0, F_z) and no moment
    (a = J^-1 (M - d x F) = 0, since d is on the axis): t = F_z/A e_z."""
    f = np.zeros((region.m0.size, 3))
    f[:, 2] = 2.0 * math.pi * force_z / region.measure * region.m0
    return f.ravel()


def rigid_fit_rows(region: AxisymmetricRegion) -> tuple[np.ndarray, np.ndarray]:
    """(L1, L0), each (6, 3N): the M.44 rigid motion [t; theta] of the region is L1 @ U1 for
    a mode-1 field U1 and L0 @ U0 for a mode-0 field. Normal equations G q = [int u; int x x u]
    (G as in loads.rigid_fit_operator); round the axis a mode-1 field has int u_x =
    pi int (U_r - U_theta) r dmu, (int x x u)_y = pi int (z (U_r - U_theta) - r U_z) r dmu and
    no other component, a mode-0 field only int u_z = 2 pi int U_z r dmu."""
    G = np.zeros((6, 6))
    G[:3, :3] = region.measure * np.eye(3)
    G[:3, 3:] = np.einsum("cjb,b->cj", EPS, np.array([0.0, 0.0, region.first_z]))
    G[3:, :3] = G[:3, 3:].T
    S = np.diag([region.second_xx, region.second_xx, region.second_zz])
    G[3:, 3:] = np.trace(S) * np.eye(3) - S
    G_inv = np.linalg.inv(G)
    n = region.m0.size
    b_x, b_ty, b_z = np.zeros((n, 3)), np.zeros((n, 3)), np.zeros((n, 3))
    b_x[:, 0], b_x[:, 1] = math.pi * region.m0, -math.pi * region.m0
    b_ty[:, 0], b_ty[:, 1], b_ty[:, 2] = math.pi * region.mz, -math.pi * region.mz, -math.pi * region.mr
    b_z[:, 2] = 2.0 * math.pi * region.m0
    L1 = G_inv[:, [0, 4]] @ np.vstack([b_x.ravel(), b_ty.ravel()])
    L0 = G_inv[:, [2]] @ b_z.ravel()[None, :]
    return L1, L0


def turn_quarter(q: np.ndarray) -> np.ndarray:
    """[t; theta] of a load case turned by +90 degrees about z (x -> y, y -> -x)."""
    return np.array([-q[1], q[0], q[2], -q[4], q[3], q[5]])


def unit_responses(mode1: np.ndarray, mode0: np.ndarray) -> np.ndarray:
    """(6, 5) rigid responses [t; theta] to unit F_x, F_y, F_z, M_x, M_y from the fitted
    responses to unit F_x and M_y (mode 1, columns of `mode1`) and F_z (mode 0). Turning
    the body by 90 degrees maps F_x to F_y and M_y to -M_x."""
    r_fx, r_my = mode1[:, 0], mode1[:, 1]
    return np.column_stack([r_fx, turn_quarter(r_fx), mode0, -turn_quarter(r_my), r_my])


@dataclass
class HarmonicSolution:
    """Section fields of the unit load cases: `mode1` (3N, 2) for unit F_x and M_y, `mode0`
    (3N,) for unit F_z [m per N or N*m]; any load (F_x, F_y, F_z, M_x, M_y) is a combination."""

    model: HarmonicModel
    mode1: np.ndarray
    mode0: np.ndarray

    def _terms(self, load):
        """(field, mode, phase) of each non-zero component of `load` (6,)."""
        fx, fy, fz, mx, my = (float(v) for v in load[:5])
        terms = [(fx * self.mode1[:, 0], 1, 0.0), (fy * self.mode1[:, 0], 1, 0.5 * math.pi),
                 (my * self.mode1[:, 1], 1, 0.0), (-mx * self.mode1[:, 1], 1, 0.5 * math.pi),
                 (fz * self.mode0, 0, 0.0)]
        return [t for t, c in zip(terms, (fx, fy, my, mx, fz)) if c != 0.0]

    def displacement(self, probe: "SectionProbe", angles: np.ndarray, load) -> np.ndarray:
        """(len(angles) * P, 3) Cartesian displacement [m] at the probe's points turned to
        each angle (layer-major, as meshes.section.revolved_points)."""
        theta = np.asarray(angles)[:, None]
        u_cyl = np.zeros((theta.shape[0], probe.n_points, 3))
        for field, mode, phase in self._terms(load):
            U = probe.values(field)  # (P, 3)
            c, s = np.cos(mode * (theta - phase)), np.sin(mode * (theta - phase))
            u_cyl[:, :, 0] += U[None, :, 0] * c
            u_cyl[:, :, 1] += U[None, :, 1] * s
            u_cyl[:, :, 2] += U[None, :, 2] * c
        ct, st = np.cos(theta), np.sin(theta)
        out = np.empty_like(u_cyl)
        out[:, :, 0] = u_cyl[:, :, 0] * ct - u_cyl[:, :, 1] * st
        out[:, :, 1] = u_cyl[:, :, 0] * st + u_cyl[:, :, 1] * ct
        out[:, :, 2] = u_cyl[:, :, 2]
        return out.reshape(-1, 3)

    def von_mises(self, probe: "SectionProbe", angles: np.ndarray, load, lam, mu) -> np.ndarray:
        """(len(angles) * P,) von Mises stress [Pa] at the probe's points turned to each
        angle; lam, mu: (P,) Lamé parameters at the points [Pa]."""
        theta = np.asarray(angles)[:, None]
        eps = np.zeros((6, theta.shape[0], probe.n_points))  # rr, tt, zz, g_rz, g_rt, g_tz
        for field, mode, phase in self._terms(load):
            a = probe.strain_amplitudes(field, mode)  # (6, P)
            c, s = np.cos(mode * (theta - phase)), np.sin(mode * (theta - phase))
            eps[:4] += a[:4, None, :] * c
            eps[4:] += a[4:, None, :] * s
        tr = eps[0] + eps[1] + eps[2]
        sig = [lam * tr + 2.0 * mu * eps[i] for i in range(3)]
        shear = [mu * eps[i] for i in range(3, 6)]
        vm2 = 0.5 * ((sig[0] - sig[1]) ** 2 + (sig[1] - sig[2]) ** 2 + (sig[2] - sig[0]) ** 2) \
            + 3.0 * (shear[0] ** 2 + shear[1] ** 2 + shear[2] ** 2)
        return np.sqrt(vm2).reshape(-1)


class SectionProbe:
    """Values and gradients of section fields at given (r, z) points (inside the section)."""

    def __init__(self, model: HarmonicModel, points: np.ndarray):
        basis = model.basis
        pts = np.ascontiguousarray(np.asarray(points, dtype=float).T)  # (2, P)
        cells = model.mesh.element_finder(mapping=basis.mapping)(*pts)
        local = basis.mapping.invF(pts[:, :, None], tind=cells)
        fields = [basis.elem.gbasis(basis.mapping, local, k, tind=cells)[0] for k in range(basis.Nbfun)]
        self.n_points = pts.shape[1]
        self.r = pts[0]
        self.cells = cells
        self.dofs = basis.element_dofs[:, cells]  # (A, P)
        self.phi = np.array([np.asarray(f)[:, 0] for f in fields])  # (A, P)
        self.grad = np.array([f.grad[:, :, 0] for f in fields])  # (A, 2, P)

    def values(self, field: np.ndarray) -> np.ndarray:
        """(P, 3) [U_r, U_theta, U_z] of a vector dof array."""
        U = field.reshape(-1, 3)[self.dofs]  # (A, P, 3)
        return (self.phi[:, :, None] * U).sum(axis=0)

    def strain_amplitudes(self, field: np.ndarray, mode: int) -> np.ndarray:
        """(6, P) amplitudes of eps_rr, eps_tt, eps_zz, g_rz (times cos n theta) and g_rt, g_tz
        (times sin n theta) of a mode field (kernels.harmonic_stiffness_upper)."""
        U = field.reshape(-1, 3)[self.dofs]  # (A, P, 3)
        val = (self.phi[:, :, None] * U).sum(axis=0).T  # (3, P)
        gr = (self.grad[:, 0, :, None] * U).sum(axis=0).T
        gz = (self.grad[:, 1, :, None] * U).sum(axis=0).T
        r, n = self.r, mode
        return np.array([gr[0], (val[0] + n * val[1]) / r, gz[2], gz[0] + gr[2],
                         gr[1] - (n * val[0] + val[1]) / r, gz[1] - n * val[2] / r])
