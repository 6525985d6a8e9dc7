"""Least-squares fit of the viscoelastic hinge stiffness (docs/model.md §3, M.2).

The hinge answers a load (F, M) applied at the ring centre with u_eq = H_u^-1 F and
psi_eq = H_psi^-1 (M_x, M_y) (equilibrium of M.17 with psi ~ (theta_x, theta_y) for
small rotations, M.15). M.2 is therefore linear in the compliances C_u = H_u^-1
(symmetric, 6 unknowns) and c_psi = 1/H_psi (2 unknowns): minimising over C and then
inverting gives the exact M.2 minimiser over H.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

# rows of the symmetric-compliance design: u_i = sum_j C_ij F_j, unknowns C11 C22 C33 C12 C13 C23
_SYM_INDEX = [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)]


@dataclass(frozen=True)
class HingeFit:
    """Fitted hinge and what it cannot represent. Units: N/m, N·m/rad, m, rad."""

    H_u: np.ndarray  # (3, 3) N/m
    H_psi: np.ndarray  # (2,) N*m/rad
    residual_u: float  # m, sqrt(sum_i |u_FE - u_eq|^2)
    residual_psi: float  # rad, sqrt(sum_i |psi_FE - psi_eq|^2)
    relative_residual: float  # M.2 residual / norm of the FE responses
    condition_number: float  # 2-norm condition of the M.2 least-squares design matrix
    flexibility: np.ndarray  # (6, 5) unconstrained LS: [u; theta] per (Fx, Fy, Fz, Mx, My)
    coupling: dict  # dimensionless coupling ratios the hinge form cannot represent
    magnitude_spread: float  # max relative change of H fitted per magnitude vs all cases


def _design(loads: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Design matrices of M.2 for the compliance unknowns: (3n, 6) and (2n, 2)."""
    n = loads.shape[0]
    D_u = np.zeros((n, 3, 6))
    for k, (a, b) in enumerate(_SYM_INDEX):
        D_u[:, a, k] += loads[:, b]
        if a != b:
            D_u[:, b, k] += loads[:, a]
    D_psi = np.zeros((n, 2, 2))
    D_psi[:, 0, 0] = loads[:, 3]
    D_psi[:, 1, 1] = loads[:, 4]
    return D_u.reshape(3 * n, 6), D_psi.reshape(2 * n, 2)


def _compliances(loads, responses):
    D_u, D_psi = _design(loads)
    if np.linalg.matrix_rank(D_u) < 6 or np.linalg.matrix_rank(D_psi) < 2:
        raise ValueError(
            "the perturbation cases do not determine the hinge: M.2 needs non-zero forces "
            "along x, y and z and moments about x and y"
        )
    c_u = np.linalg.lstsq(D_u, responses[:, :3].ravel(), rcond=None)[0]
    c_psi = np.linalg.lstsq(D_psi, responses[:, 3:5].ravel(), rcond=None)[0]
    C_u = np.zeros((3, 3))
    for value, (a, b) in zip(c_u, _SYM_INDEX):
        C_u[a, b] = C_u[b, a] = value
    return C_u, c_psi, D_u, D_psi


def fit_hinge(loads: np.ndarray, responses: np.ndarray, groups: np.ndarray | None = None) -> HingeFit:
    """Fit M.2. loads: (n, 6) [Fx Fy Fz (N), Mx My Mz (N·m)] applied at the ring centre;
    responses: (n, 6) [u (m), theta (rad)] from the rigid fit; groups: (n,) label of the
    magnitude set each case belongs to (for the spread), optional."""
    loads = np.asarray(loads, dtype=float)
    responses = np.asarray(responses, dtype=float)
    C_u, c_psi, D_u, D_psi = _compliances(loads, responses)
    eig = np.linalg.eigvalsh(C_u)
    if eig.min() <= 0.0 or np.any(c_psi <= 0.0):
        raise ValueError(
            f"fitted hinge compliance is not positive definite (eigenvalues {eig}, bending "
            f"{c_psi}); the FE model is not restrained or the loads are inconsistent"
        )
    H_u, H_psi = np.linalg.inv(C_u), 1.0 / c_psi
    H_u = 0.5 * (H_u + H_u.T)
    res_u = responses[:, :3] - loads[:, :3] @ C_u
    res_psi = responses[:, 3:5] - loads[:, 3:5] * c_psi
    design = np.block([[D_u, np.zeros((D_u.shape[0], 2))], [np.zeros((D_psi.shape[0], 6)), D_psi]])
    data_norm = np.linalg.norm(responses[:, :5])
    residual = np.hypot(np.linalg.norm(res_u), np.linalg.norm(res_psi))
    flexibility = np.linalg.lstsq(loads[:, :5], responses, rcond=None)[0].T
    return HingeFit(
        H_u=H_u,
        H_psi=H_psi,
        residual_u=float(np.linalg.norm(res_u)),
        residual_psi=float(np.linalg.norm(res_psi)),
        relative_residual=float(residual / data_norm) if data_norm > 0 else 0.0,
        condition_number=float(np.linalg.cond(design)),
        flexibility=flexibility,
        coupling=coupling_ratios(flexibility),
        magnitude_spread=_magnitude_spread(loads, responses, groups, H_u, H_psi),
    )


def coupling_ratios(flexibility: np.ndarray) -> dict:
    """Coupling terms the hinge form cannot represent, as ratios of the flexibility.

    With G5 the flexibility of (u, theta_x, theta_y) under (F, M_x, M_y), the ratio
    G5_ij / sqrt(G5_ii G5_jj) is 0 for an uncoupled pair and bounded by 1 for an SPD
    flexibility. The hinge keeps the u-u block (H_u is full) but sets to zero the
    translation-rotation block and the theta_x-theta_y cross term; theta_z (spin) is free.
    """
    G5 = flexibility[:5, :5]
    d = np.sqrt(np.abs(np.diag(G5)))
    ratio = G5 / np.outer(d, d)
    return {
        "translation_rotation_max": float(np.abs(np.r_[ratio[:3, 3:].ravel(), ratio[3:, :3].ravel()]).max()),
        "bending_cross": float(max(abs(ratio[3, 4]), abs(ratio[4, 3]))),
        "translation_per_moment": ratio[:3, 3:].tolist(),  # rows u_x,u_y,u_z; cols M_x,M_y
        "rotation_per_force": ratio[3:, :3].tolist(),  # rows theta_x,theta_y; cols F_x,F_y,F_z
        "reciprocity_asymmetry": float(np.abs(ratio - ratio.T).max()),
        "spin_per_load_rad": flexibility[5, :].tolist(),  # theta_z per (F [N], M [N*m]), raw
    }


def _magnitude_spread(loads, responses, groups, H_u, H_psi) -> float:
    """Largest relative change of H when fitted on one magnitude set alone."""
    if groups is None:
        return 0.0
    spread = 0.0
    for g in np.unique(groups):
        pick = groups == g
        try:
            C_u, c_psi, _, _ = _compliances(loads[pick], responses[pick])
        except ValueError:
            continue
        spread = max(
            spread,
            np.linalg.norm(np.linalg.inv(C_u) - H_u) / np.linalg.norm(H_u),
            float(np.max(np.abs(1.0 / c_psi - H_psi) / H_psi)),
        )
    return float(spread)
