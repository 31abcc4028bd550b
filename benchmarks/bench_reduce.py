"""Benchmark: balanced truncation of 200-state models, every method.

1. A random 200-state positive-real MIMO model (6 inputs and outputs, D = 0 like a
   radiation model; built through the KYP lemma) reduced to 40 states by every method
   of :func:`cummins.radiation.reduce.balanced_truncation`, each timed (best of 3), and by
   the naive form of Unneland (2007) Table 5.1 (Cholesky factors of the gramians, T from the
   inverse of a factor) as the reference measured in the same run. Printed: time, ratio
   to the naive Lyapunov reduction, ‖G − G_r‖∞ / ‖G‖∞, Glover's bound (Lyapunov), and
   the positive-realness margin min_ω λ_min(S (G_r + G_rᴴ) S) (DOF-scaled; the PR
   methods guarantee ≥ −2ε, ε = 10⁻³).
2. The same kind of model with 40 uncontrollable states (a singular gramian): the
   naive form fails, the square-root form does not.
3. The tanker's ERA realization at order 11 per coupling stacked into one MIMO model
   (about 200 states), reduced by Lyapunov BT as a MIMO model (which mixes the
   couplings), and coupling by coupling by :func:`cummins.radiation.reduce.reduce_radiation_model`
   to the default FD fit's total order.
4. The default (common-pole) models of the tanker, the float and spar and a corpus WEC
   reduced block by block (``tol`` 0.02 and 0.01), against the reference measured in the
   same run: the same fit with fewer common poles (``max_order``, the largest whose total
   order is at most the reduction's). Printed: states, time, motion-RAO error (the
   scoreboard's), passivity by the independent sweep.

Run: ``python benchmarks/bench_reduce.py``.
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")


from pathlib import Path

import numpy as np
import scipy.linalg

import cummins
from _timing import SHARED_DATA, timed
from cummins.errors import FitError
from cummins.radiation.fit import PREVIOUS_DEFAULT, fit_radiation
from cummins.radiation.reduce import (
    METHODS,
    balanced_truncation,
    frequency_response,
    hinf_norm,
    lyapunov_gramians,
    reduce_radiation_model,
    reduce_to_motion_tolerance,
)

DATA = SHARED_DATA / "mss" / "tanker" / "tanker.1"
STATES, PORTS, ORDER = 200, 6, 40


def random_positive_real(rng, n, m):
    """KYP with X = I: A = S − M (Aᵀ + A = −2M ≺ 0), C = Bᵀ, D = 0, hidden by a similarity."""
    x = rng.normal(size=(n, n))
    s = rng.normal(size=(n, n))
    a = 0.5 * (s - s.T) - (x @ x.T / n + 0.02 * np.eye(n))
    b = rng.normal(size=(n, m))
    t = np.eye(n) + 0.3 * rng.normal(size=(n, n)) / np.sqrt(n)
    t_inv = np.linalg.inv(t)
    return t @ a @ t_inv, t @ b, b.T @ t_inv


def naive_lyapunov(a, b, c, order):
    """Unneland (2007) Table 5.1 as printed: Cholesky factors, T = Σ^{1/2} Uᵀ L_M⁻¹."""
    p, q = lyapunov_gramians(a, b, c)
    l_m = scipy.linalg.cholesky(p, lower=True)
    l_n = scipy.linalg.cholesky(q, lower=True)
    u, sigma, vt = np.linalg.svd(l_m.T @ l_n)
    t = np.sqrt(sigma)[:, None] * (u.T @ np.linalg.inv(l_m))
    t_inv = scipy.linalg.solve_triangular(l_n.T, vt.T, lower=False) * np.sqrt(sigma)[None, :]
    a_b, b_b, c_b = t @ a @ t_inv, t @ b, c @ t_inv
    return a_b[:order, :order], b_b[:order], c_b[:, :order], sigma


def relative_error(a, b, c, a_r, b_r, c_r, norm):
    a_e = scipy.linalg.block_diag(a, a_r)
    return hinf_norm(a_e, np.vstack([b, b_r]), np.hstack([c, -c_r]))[0] / norm


def pr_margin(a_r, b_r, c_r, scale, omega):
    g = frequency_response(a_r, b_r, c_r, None, omega)
    h = scale[None, :, None] * (g + np.conj(np.swapaxes(g, 1, 2))) * scale[None, None, :]
    return float(np.linalg.eigvalsh(h)[:, 0].min())


def random_model_benchmark() -> None:
    a, b, c = random_positive_real(np.random.default_rng(2024), STATES, PORTS)
    norm = hinf_norm(a, b, c)[0]
    omega = np.geomspace(1e-3, 1e3, 600)
    print(f"random PR model: {STATES} states, {PORTS}×{PORTS}, D = 0, reduced to {ORDER}")
    t_naive, naive = timed(lambda: naive_lyapunov(a, b, c, ORDER))
    err_naive = relative_error(a, b, c, *naive[:3], norm)
    print(f"   {'method':<16} {'time [s]':>9} {'ratio':>7} {'error/‖G‖∞':>11} {'bound/‖G‖∞':>11}")
    print(f"   {'naive Table 5.1':<16} {t_naive:9.3f} {1.0:7.2f} {err_naive:11.3e} {'':>11}")
    scale = None
    for method in METHODS:
        seconds, red = timed(lambda m=method: balanced_truncation(a, b, c, order=ORDER, method=m))
        err = relative_error(a, b, c, red.a, red.b, red.c, norm)
        bound = f"{red.error_bound / norm:11.3e}" if red.error_bound is not None else ""
        scale = red.dof_scale if red.dof_scale.size else scale
        margin = pr_margin(red.a, red.b, red.c, scale, omega) if scale is not None else np.nan
        print(
            f"   {method:<16} {seconds:9.3f} {seconds / t_naive:7.2f} {err:11.3e} {bound:>11}"
            f"   PR margin {margin: .2e}"
        )


def non_minimal_benchmark() -> None:
    """The random model with 40 of its states made uncontrollable (zero rows of B, an
    upper block-triangular A): P is singular, Table 5.1's Cholesky factor does not exist."""
    a, b, c = random_positive_real(np.random.default_rng(7), STATES, PORTS)
    hidden = 40
    a[STATES - hidden :, : STATES - hidden] = 0.0
    b[STATES - hidden :] = 0.0
    norm = hinf_norm(a, b, c)[0]
    print(f"non-minimal model: {STATES} states, {hidden} uncontrollable, reduced to {ORDER}")
    try:
        naive_lyapunov(a, b, c, ORDER)
        print("   naive Table 5.1: succeeded")
    except (np.linalg.LinAlgError, ValueError) as exc:
        print(f"   naive Table 5.1: fails ({str(exc)[:70]})")
    seconds, red = timed(lambda: balanced_truncation(a, b, c, order=ORDER))
    err = relative_error(a, b, c, red.a, red.b, red.c, norm)
    print(
        f"   square-root lyapunov: {seconds:.3f} s, error/‖G‖∞ {err:.3e}, "
        f"bound/‖G‖∞ {red.error_bound / norm:.3e}"
    )


def tanker_benchmark() -> None:
    if not DATA.is_file():
        print(f"{DATA} not found: tanker part skipped")
        return
    ds = cummins.read(DATA)
    # the per-coupling FD fit (reduce works coupling by coupling; the default common-pole
    # model is already near its smallest order and is refused)
    fd = fit_radiation(ds, PREVIOUS_DEFAULT)
    pairs = [(k.influenced, k.radiating) for k in fd.couplings if k.influenced <= k.radiating]
    era = fit_radiation(ds, method="realization", orders=dict.fromkeys(pairs, 11))
    a, b, c = era.A, era.B, era.C
    norm = hinf_norm(a, b, c)[0]
    print(
        f"tanker ERA model: {era.total_order} states ({len(era.couplings)} couplings), "
        f"FD fit total order {fd.total_order}"
    )
    seconds, red = timed(lambda: balanced_truncation(a, b, c, order=fd.total_order))
    err = relative_error(a, b, c, red.a, red.b, red.c, norm)
    print(
        f"   MIMO Lyapunov BT to {fd.total_order}: {seconds:.3f} s, error/‖G‖∞ {err:.3e}, "
        f"bound/‖G‖∞ {red.error_bound / norm:.3e}"
    )
    try:
        t_naive, naive = timed(lambda: naive_lyapunov(a, b, c, fd.total_order))
        err_naive = relative_error(a, b, c, *naive[:3], norm)
        print(
            f"   naive Table 5.1 to {fd.total_order}: {t_naive:.3f} s "
            f"(square root / naive {seconds / t_naive:.2f}), error/‖G‖∞ {err_naive:.3e}"
        )
    except (np.linalg.LinAlgError, FitError) as exc:
        print(f"   naive Table 5.1: fails ({exc})")
    try:
        seconds_pr, _ = timed(
            lambda: balanced_truncation(a, b, c, order=fd.total_order, method="mixed")
        )
        print(f"   MIMO mixed BT to {fd.total_order}: {seconds_pr:.3f} s")
    except FitError as exc:
        print(f"   MIMO mixed BT: refused ({str(exc)[:90]}…)")
    tables = {}
    for method in ("lyapunov", "mixed"):
        seconds_c, per = timed(
            lambda m=method: reduce_radiation_model(era, order=fd.total_order, method=m, data=ds)
        )
        upper = [k for k in per.couplings if k.influenced <= k.radiating]
        worst = min(min(k.metrics["r2_added_mass"], k.metrics["r2_damping"]) for k in upper)
        print(
            f"   per coupling ({method}) to {per.total_order}: {seconds_c:.3f} s "
            f"({seconds_c / seconds:.1f}× the MIMO BT), worst R² of A or B {worst:.4f}"
        )
        tables[method] = upper
    print("   lyapunov, per coupling: order, R² against the data, Glover bound and change")
    print("   coupling  order  R2(A)   R2(B)   bound/max|K|  change/max|K|  FD: R2(A)  R2(B)")
    for k in tables["lyapunov"]:
        m = k.metrics
        original = era.coupling(k.influenced, k.radiating)
        peak = hinf_norm(original.a, original.b, original.c)[0]
        ref = fd.coupling(k.influenced, k.radiating).metrics
        print(
            f"   {k.influenced + 1}{k.radiating + 1:<8d} {m['reduction_order_before']:2d}→"
            f"{m['reduction_order_after']:<2d} {m['r2_added_mass']:.4f}  {m['r2_damping']:.4f}"
            f"  {m['reduction_error_bound'] / peak:11.3e}  {m['reduction_hinf_relative']:11.3e}"
            f"    {ref['r2_added_mass']:.4f}  {ref['r2_damping']:.4f}"
        )


BLOCK_CASES = (
    ("tanker", SHARED_DATA / "mss" / "tanker" / "tanker.1"),
    ("float and spar", Path(__file__).resolve().parents[1] / "tests" / "data"
     / "float_spar_capytaine.nc"),
)  # fmt: skip


def blocks_benchmark() -> None:
    """Block reduction of the default model against a refit with fewer common poles."""
    import warnings

    from cummins.radiation.fit.scorecard import motion_rao_error, passivity_margin

    print("default (common-pole) models reduced block by block, against a refit with fewer poles")
    print(
        f"   {'case':<16} {'model':<28} {'states':>6} {'time [s]':>9} {'RAO err':>8} {'passive':>8}"
    )

    def row(case, what, model, seconds, ds):
        rao = motion_rao_error(ds, model).error
        passive = passivity_margin(model) >= -1e-6
        print(
            f"   {case:<16} {what:<28} {model.total_order:6d} {seconds:9.2f} "
            f"{100 * rao:7.2f}% {'yes' if passive else 'NO':>8}"
        )

    for case, path in BLOCK_CASES:
        if not path.exists():
            print(f"   {case}: {path} not found, skipped")
            continue
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            ds = cummins.read(path)
            t_fit, model = timed(lambda ds=ds: fit_radiation(ds), repeat=1)
            row(case, "default fit", model, t_fit, ds)
            reduced = {}
            for tol in (0.02, 0.01):
                reduced[tol] = timed(
                    lambda m=model, ds=ds, tol=tol: reduce_radiation_model(m, tol=tol, data=ds),
                    repeat=1,
                )
            refits = []  # (poles, time, model) while the order stays below both reductions
            largest = max(small.total_order for _, small in reduced.values())
            for count in range(2, 40):
                t_try, trial = timed(lambda ds=ds, c=count: fit_radiation(ds, max_order=c), 1)
                if trial.total_order > largest:
                    break
                refits.append((count, t_try, trial))
            for tol, (t_red, small) in reduced.items():
                row(case, f"reduced, tol {tol:g}", small, t_red, ds)
                fitting = [x for x in refits if x[2].total_order <= small.total_order]
                if fitting:
                    count, t_refit, refit = fitting[-1]
                    row(case, f"refit, ≤ {count} poles", refit, t_refit, ds)
            # the fewest states whose motions stay within 1 % (bisection over tol)
            t_motion, kept = timed(
                lambda m=model, ds=ds: reduce_to_motion_tolerance(m, ds, 0.01), repeat=1
            )
            used = kept.attrs.get("reduction_tol", "—")
            row(case, f"motion-tol 0.01 (tol {used})", kept, t_motion, ds)
            ratio = t_motion / reduced[0.02][0]
            print(f"   {'':<16} time of motion-tol 0.01 / tol 0.02: {ratio:.1f}×")


def main() -> None:
    random_model_benchmark()
    non_minimal_benchmark()
    tanker_benchmark()
    blocks_benchmark()


if __name__ == "__main__":
    main()
