"""Direct LAPACK calls of the pole relocation (:mod:`cummins.radiation.fit.vector`): the
numbers numpy's ``linalg`` wrappers give (``eigvals``, ``lstsq``, ``qr(mode="r")``), without
their checks and copies (the order search relocates a block's poles hundreds of times)."""

from __future__ import annotations

import functools

import numpy as np
import scipy.linalg.lapack
from numpy.typing import NDArray

_EPS = np.finfo(float).eps


def eigenvalues(matrix: NDArray) -> NDArray[np.complex128]:
    """The eigenvalues of a real square ``matrix``: LAPACK's dgeev without eigenvectors,
    its workspace as ``numpy.linalg.eigvals`` asks for it (the same values), without that
    wrapper's checks but the one for infinities and NaNs."""
    if not np.isfinite(matrix).all():
        raise np.linalg.LinAlgError("Array must not contain infs or NaNs")
    wr, wi, _, _, info = scipy.linalg.lapack.dgeev(
        matrix, compute_vl=0, compute_vr=0, lwork=_eig_workspace(matrix.shape[0])
    )
    if info:
        raise np.linalg.LinAlgError(f"eigenvalues did not converge (LAPACK info {info})")
    return wr + 1j * wi


@functools.lru_cache(maxsize=64)
def _eig_workspace(size: int) -> int:
    """dgeev's optimal workspace for a size × size matrix without eigenvectors."""
    return int(scipy.linalg.lapack.dgeev_lwork(size, compute_vl=0, compute_vr=0)[0])


def least_squares(matrix: NDArray, rhs: NDArray) -> NDArray:
    """The minimum-norm least-squares solution of ``matrix`` x = ``rhs``: LAPACK's dgelsd
    with the cut-off of ``numpy.linalg.lstsq(rcond=None)`` (machine ε × the larger
    dimension), the same numbers without that wrapper's checks (the relocation solves one
    per iteration, the residues one per element and order)."""
    rows, columns = matrix.shape
    if rows < columns:  # LAPACK's right-hand side holds the solution
        rhs = np.concatenate([rhs, np.zeros(columns - rows)])
    lwork, iwork = _lstsq_workspace(rows, columns)
    x, _, _, info = scipy.linalg.lapack.dgelsd(
        matrix, rhs, lwork=lwork, size_iwork=iwork, cond=_EPS * max(rows, columns)
    )
    if info:
        raise np.linalg.LinAlgError(f"least squares failed (LAPACK info {info})")
    return x[:columns]


@functools.lru_cache(maxsize=256)
def _lstsq_workspace(rows: int, columns: int) -> tuple[int, int]:
    """dgelsd's optimal workspace and integer workspace for one right-hand side."""
    lwork, iwork, _ = scipy.linalg.lapack.dgelsd_lwork(rows, columns, 1, -1)
    return int(lwork), int(iwork)


def r_factor(matrix: NDArray, start: int, out: NDArray) -> None:
    """The trailing block R[start:, start:] of the triangular factor R of the Householder
    QR of a Fortran-ordered ``matrix`` (rows ≥ columns), factored in place, written to
    ``out``: LAPACK's dgeqrf with its optimal workspace, as ``numpy.linalg.qr(mode="r")``
    calls it (the same R, bit for bit), without the copies."""
    rows, columns = matrix.shape
    qr, _, _, info = scipy.linalg.lapack.dgeqrf(
        matrix, lwork=_qr_workspace(rows, columns), overwrite_a=1
    )
    if info:
        raise np.linalg.LinAlgError(f"QR factorisation failed (LAPACK info {info})")
    out[...] = qr[start:columns, start:]
    out[_strictly_lower(columns - start)] = 0.0


@functools.lru_cache(maxsize=64)
def _strictly_lower(size: int) -> tuple[NDArray, NDArray]:
    """The indices below the diagonal of a square matrix of ``size``."""
    return np.tril_indices(size, -1)


@functools.lru_cache(maxsize=256)
def _qr_workspace(rows: int, columns: int) -> int:
    """dgeqrf's optimal workspace for a rows × columns matrix."""
    return int(scipy.linalg.lapack.dgeqrf_lwork(rows, columns)[0])
