"""Motion records: reading, segmenting, and aligning predictions with measurements.

A *record* is an :class:`xarray.Dataset` on a uniform ``time`` axis (s) with

* ``motion`` (time, dof): the measured motions, m and rad, about the reference point and
  axes of the hydrodynamic model they will be compared with;
* optionally ``velocity`` (time, dof), m/s and rad/s (else differentiated from motion);
* optionally ``excitation_force`` (time, dof), N and N·m: the first-order wave force
  (predicted, or measured on a captive model);
* optionally ``wave_elevation`` (time), m, at the origin, with attribute ``heading_deg``
  (direction of wave travel): the force is then computed with
  :func:`excitation_from_elevation`.

The output of ``cummins simulate`` (``run.nc``) is a record (its ``external_force`` is
read as the excitation). Field records are read from CSV with units in the header
(:func:`read_record`). Scaling and shifting of predicted against measured signals follow
de Haan (2022) §3.2.1: γ = RMS(predicted)/RMS(measured), and the lag of the largest
cross-correlation within a maximum.
"""

from __future__ import annotations

import csv
import os
import re
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from cummins.errors import HydroDataError
from cummins.hydrodb import DOF_NAMES, is_rotation

#: Conversion of the units accepted in a record's header to SI, by kind of quantity.
UNITS: dict[str, dict[str, float]] = {
    "time": {"s": 1.0, "ms": 1e-3, "min": 60.0},
    "length": {"m": 1.0, "cm": 1e-2, "mm": 1e-3},
    "angle": {"rad": 1.0, "deg": np.pi / 180.0},
    "speed": {"m/s": 1.0, "cm/s": 1e-2, "mm/s": 1e-3},
    "angular speed": {"rad/s": 1.0, "deg/s": np.pi / 180.0},
    "force": {"n": 1.0, "kn": 1e3, "mn": 1e6},
    "moment": {"nm": 1.0, "knm": 1e3, "mnm": 1e6},
}
#: Relative jitter of the time step tolerated in a record (sampling clocks of loggers).
TIME_JITTER = 1e-3

_HEADER = re.compile(r"^\s*(?P<name>[^\[\(]+?)\s*(?:[\[\(](?P<unit>[^\]\)]*)[\]\)])?\s*$")


@dataclass(frozen=True)
class _Column:
    variable: str  # motion, velocity, excitation_force, wave_elevation, time
    dof: str | None
    kind: str


def _column(name: str, path, line: int = 1) -> _Column:
    """What a header name means: ``time``, ``Roll``, ``Roll velocity``, ``Roll force`` /
    ``Roll moment``, ``wave elevation`` (case and _ or - free)."""
    key = re.sub(r"[\s_\-]+", " ", name.strip().lower())
    if key in ("time", "t"):
        return _Column("time", None, "time")
    if key in ("wave elevation", "wave", "eta", "elevation"):
        return _Column("wave_elevation", None, "length")
    words = key.split(" ")
    dof = next((d for d in DOF_NAMES if d.lower() == words[0]), None)
    if dof is not None:
        rot = is_rotation(dof)
        rest = " ".join(words[1:])
        if rest in ("", "motion", "displacement", "angle"):
            return _Column("motion", dof, "angle" if rot else "length")
        if rest in ("velocity", "rate", "speed"):
            return _Column("velocity", dof, "angular speed" if rot else "speed")
        if rest in ("force", "moment", "excitation", "excitation force", "wave force"):
            return _Column("excitation_force", dof, "moment" if rot else "force")
    raise HydroDataError(
        f"column {name!r} is not a record quantity",
        path=path,
        line=line,
        hint="name the columns time, <DOF> (motion), <DOF> velocity, <DOF> force (or "
        f"moment) and wave elevation, with DOF one of {', '.join(DOF_NAMES)}, units in "
        "brackets: e.g. 'Roll [deg]', 'Roll moment [kN m]'",
    )


def _unit_factor(unit: str | None, column: _Column, name: str, path) -> float:
    table = UNITS[column.kind]
    if unit is None or not unit.strip():
        raise HydroDataError(
            f"column {name!r} has no unit",
            path=path,
            line=1,
            hint=f"write it in brackets, e.g. '{name} [{next(iter(table))}]' "
            f"(accepted: {', '.join(table)})",
        )
    key = re.sub(r"[\s\*\.·]+", "", unit.strip().lower())
    if key not in table:
        raise HydroDataError(
            f"column {name!r}: unit {unit!r} is not one of a {column.kind}",
            path=path,
            line=1,
            hint=f"accepted: {', '.join(table)}",
        )
    return table[key]


def read_record(path: str | os.PathLike[str], *, heading_deg: float | None = None) -> xr.Dataset:
    """Read a motion record from CSV (units in the header) or NetCDF.

    Parameters
    ----------
    path
        ``.csv`` (or ``.txt``): a header line naming each column with its unit in
        brackets, e.g. ``time [s], Roll [deg], Heave [m], Roll moment [kN m]``; comma,
        semicolon or tab separated; lines starting with ``#`` are comments. ``.nc``: a
        record (module docstring) or the ``run.nc`` of ``cummins simulate``.
    heading_deg
        Direction of wave travel, degrees, when the record holds a wave elevation.

    Returns
    -------
    xarray.Dataset
        The record in SI units (m, rad, N, N·m), validated by :func:`validate_record`.

    Raises
    ------
    HydroDataError
        Unknown column, missing or wrong unit, a line with a wrong number of values or a
        value that is not a number (naming file and line), NaN, non-uniform time.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> f = pathlib.Path(tempfile.mkdtemp()) / "decay.csv"
    >>> _ = f.write_text("time [s], Roll [deg]\\n0, 10\\n0.5, 9\\n1, 7\\n")
    >>> round(float(read_record(f).motion.sel(dof="Roll")[0]), 4)  # rad
    0.1745
    """
    p = Path(path)
    if not p.is_file():
        raise HydroDataError("no such file", path=p)
    if p.suffix.lower() in (".nc", ".nc4", ".netcdf"):
        record = _read_netcdf(p)
    else:
        record = _read_csv(p)
    if heading_deg is not None:
        record.attrs["heading_deg"] = float(heading_deg)
    record.attrs.setdefault("source_file", str(p))
    return validate_record(record, path=p)


def read_wave_elevation(path: str | os.PathLike[str]) -> xr.DataArray:
    """A record of the wave elevation at the origin: η(t), m, on uniform times.

    Parameters
    ----------
    path
        ``.csv`` (or ``.txt``) with a header naming the columns with their units, as
        :func:`read_record` reads them: ``time [s], wave elevation [m]`` (``eta``,
        ``wave``, ``elevation`` also name it; cm and mm are converted; other record
        columns may be present and are ignored); or ``.nc``: a run of ``cummins
        simulate`` (its ``wave_elevation``).

    Returns
    -------
    xarray.DataArray
        ``wave_elevation`` (time), m; attribute ``source_file``.

    Raises
    ------
    HydroDataError
        No wave-elevation column, a malformed line (naming file and line), NaN,
        non-uniform time.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> f = pathlib.Path(tempfile.mkdtemp()) / "eta.csv"
    >>> _ = f.write_text("time [s], wave elevation [cm]\\n0, 10\\n0.5, 12\\n1, 7\\n")
    >>> read_wave_elevation(f).values.tolist()
    [0.1, 0.12, 0.07]
    """
    p = Path(path)
    if not p.is_file():
        raise HydroDataError("no such file", path=p)
    if p.suffix.lower() in (".nc", ".nc4", ".netcdf"):
        try:
            with xr.open_dataset(p, engine="h5netcdf") as f:
                ds = f.load()
        except (OSError, ValueError) as exc:
            raise HydroDataError(f"not a readable NetCDF file ({exc})", path=p) from None
        if "wave_elevation" not in ds or ds.wave_elevation.dims != ("time",):
            raise HydroDataError("the file has no wave_elevation(time)", path=p)
        t = np.asarray(ds.time.values, dtype=float)
        eta = np.asarray(ds.wave_elevation.values, dtype=float)
        _check_time(t, p)
    else:
        columns, values, t = _parse_csv(p)
        kinds = [c.variable for c in columns]
        if "wave_elevation" not in kinds:
            raise HydroDataError(
                "the file has no wave elevation column",
                path=p,
                line=1,
                hint="name it 'wave elevation [m]' next to 'time [s]'",
            )
        eta = values[:, kinds.index("wave_elevation")]
    if not np.all(np.isfinite(eta)):
        k = int(np.flatnonzero(~np.isfinite(eta))[0])
        raise HydroDataError(f"the wave elevation is not finite at t = {t[k]:.6g} s", path=p)
    uniform = t[0] + (t[1] - t[0]) * np.arange(t.size)
    return xr.DataArray(
        eta,
        dims=("time",),
        coords={"time": uniform},
        name="wave_elevation",
        attrs={"units": "m", "source_file": str(p)},
    )


def _read_netcdf(p: Path) -> xr.Dataset:
    try:
        with xr.open_dataset(p, engine="h5netcdf") as f:
            ds = f.load()
    except (OSError, ValueError) as exc:
        raise HydroDataError(f"not a readable NetCDF file ({exc})", path=p) from None
    if "motion" not in ds:
        raise HydroDataError(
            "the file has no 'motion' variable (time, dof)",
            path=p,
            hint="a record holds motion(time, dof); run.nc of `cummins simulate` is one",
        )
    keep = [v for v in ("motion", "velocity", "excitation_force", "wave_elevation") if v in ds]
    if "excitation_force" not in ds and "external_force" in ds:
        ds = ds.rename({"external_force": "excitation_force"})
        keep.append("excitation_force")
    out = ds[keep]
    out.attrs = dict(ds.attrs)
    return out


def _parse_csv(p: Path) -> tuple[list[_Column], NDArray, NDArray]:
    """The columns, the values in SI units (rows × columns) and the checked times of a
    CSV record (units in the header, see :func:`read_record`)."""
    try:
        text = p.read_text(encoding="utf-8", errors="strict")
    except (OSError, UnicodeDecodeError) as exc:
        raise HydroDataError(f"cannot read the file as text ({exc})", path=p) from None
    lines = [(k + 1, s) for k, s in enumerate(text.splitlines()) if s.strip()]
    lines = [(k, s) for k, s in lines if not s.lstrip().startswith("#")]
    if len(lines) < 3:
        raise HydroDataError("a record needs a header line and at least two samples", path=p)
    header_line, header = lines[0]
    delimiter = ";" if ";" in header else ("\t" if "\t" in header else ",")
    names = next(csv.reader([header], delimiter=delimiter))
    columns, factors = [], []
    for name in names:
        m = _HEADER.match(name)
        label = m.group("name") if m else name
        col = _column(label, p, header_line)
        columns.append(col)
        factors.append(_unit_factor(m.group("unit") if m else None, col, label.strip(), p))
    if [c.variable for c in columns].count("time") != 1:
        raise HydroDataError("the header needs exactly one 'time [s]' column", path=p, line=1)
    seen = set()
    for c, name in zip(columns, names, strict=True):
        if (c.variable, c.dof) in seen:
            raise HydroDataError(f"column {name.strip()!r} appears twice", path=p, line=1)
        seen.add((c.variable, c.dof))
    values = np.empty((len(lines) - 1, len(names)))
    for row, (number, line) in enumerate(lines[1:]):
        fields = next(csv.reader([line], delimiter=delimiter))
        if len(fields) != len(names):
            raise HydroDataError(
                f"expected {len(names)} values, found {len(fields)}", path=p, line=number
            )
        for k, field in enumerate(fields):
            try:
                values[row, k] = float(field)
            except ValueError:
                raise HydroDataError(
                    f"{field.strip()!r} in column {names[k].strip()!r} is not a number",
                    path=p,
                    line=number,
                ) from None
            if not np.isfinite(values[row, k]):
                raise HydroDataError(
                    f"{names[k].strip()!r} is not finite ({field.strip()})",
                    path=p,
                    line=number,
                    hint="cut the record at the gap (two files) or fill it before identifying",
                )
    values *= np.asarray(factors)
    k_time = [c.variable for c in columns].index("time")
    t = values[:, k_time]
    _check_time(t, p, [n for n, _ in lines[1:]])
    return columns, values, t


def _read_csv(p: Path) -> xr.Dataset:
    columns, values, t = _parse_csv(p)
    dofs = [d for d in DOF_NAMES if any(c.dof == d for c in columns if c.variable == "motion")]
    if not dofs:
        raise HydroDataError("the record has no motion column (e.g. 'Roll [deg]')", path=p)
    data = {}
    for variable in ("motion", "velocity", "excitation_force"):
        cols = {c.dof: k for k, c in enumerate(columns) if c.variable == variable}
        if not cols:
            continue
        missing = [d for d in dofs if d not in cols]
        extra = [d for d in cols if d not in dofs]
        if extra:
            raise HydroDataError(
                f"{variable} of {', '.join(extra)} but no motion of it", path=p, line=1
            )
        if missing and variable == "velocity":
            raise HydroDataError(
                f"velocity columns for {', '.join(missing)} are missing: give all or none",
                path=p,
                line=1,
            )
        data[variable] = (
            ("time", "dof"),
            np.stack([values[:, cols[d]] if d in cols else np.zeros(t.size) for d in dofs], 1),
        )
    if "wave_elevation" in [c.variable for c in columns]:
        k = [c.variable for c in columns].index("wave_elevation")
        data["wave_elevation"] = ("time", values[:, k])
    return xr.Dataset(data, coords={"time": t, "dof": dofs})


def _check_time(t: NDArray, path, line_numbers=None) -> None:
    step = np.diff(t)
    if t.size < 2:
        raise HydroDataError("a record needs at least two samples", path=path)
    dt = float(np.median(step))
    if not dt > 0:
        raise HydroDataError("time does not increase", path=path)
    bad = np.flatnonzero(np.abs(step - dt) > TIME_JITTER * dt)
    if bad.size:
        k = int(bad[0]) + 1
        line = None if line_numbers is None else line_numbers[k]
        raise HydroDataError(
            f"the time step changes at t = {t[k]:.6g} s ({step[k - 1]:.6g} s instead of "
            f"{dt:.6g} s)",
            path=path,
            line=line,
            hint="records must be sampled uniformly: resample it (e.g. numpy.interp onto "
            "a uniform grid) or cut it at the gap",
        )


def validate_record(record: xr.Dataset, *, path=None) -> xr.Dataset:
    """Check a record (module docstring) and return it with a uniform ``time`` axis.

    Raises HydroDataError for missing ``motion``, unknown DOF labels, NaN (naming the
    variable, DOF and time), non-uniform time and mismatched shapes.
    """
    where = path if path is not None else record.attrs.get("source_file") or None
    if "motion" not in record or record.motion.dims != ("time", "dof"):
        raise HydroDataError("a record needs motion(time, dof)", path=where)
    unknown = [str(d) for d in record.dof.values if str(d) not in DOF_NAMES]
    if unknown:
        raise HydroDataError(
            f"unknown DOF labels {unknown}", path=where, hint=f"use {', '.join(DOF_NAMES)}"
        )
    t = record.time.values.astype(float)
    _check_time(t, where)
    for name in ("motion", "velocity", "excitation_force", "wave_elevation"):
        if name not in record:
            continue
        values = np.asarray(record[name].values, dtype=float)
        bad = ~np.isfinite(values)
        if bad.any():
            idx = np.argwhere(bad)[0]
            dof = f" of {record.dof.values[idx[1]]}" if values.ndim == 2 else ""
            raise HydroDataError(
                f"{name}{dof} is not finite at t = {t[idx[0]]:.6g} s",
                path=where,
                hint="cut the record at the gap or fill it before identifying",
            )
    out = record.assign_coords(time=t[0] + (t[1] - t[0]) * np.arange(t.size))
    out.time.attrs["units"] = "s"
    return out


def make_record(
    t: ArrayLike,
    motion: ArrayLike,
    dofs: tuple[str, ...] | list[str],
    *,
    excitation_force: ArrayLike | None = None,
    velocity: ArrayLike | None = None,
    wave_elevation: ArrayLike | None = None,
    heading_deg: float | None = None,
) -> xr.Dataset:
    """A record from arrays in SI units (motion (N, n) m/rad, force (N, n) N/N·m)."""
    t = np.asarray(t, dtype=float).reshape(-1)
    data = {"motion": (("time", "dof"), np.asarray(motion, dtype=float).reshape(t.size, -1))}
    for name, value in (("excitation_force", excitation_force), ("velocity", velocity)):
        if value is not None:
            data[name] = (("time", "dof"), np.asarray(value, dtype=float).reshape(t.size, -1))
    if wave_elevation is not None:
        data["wave_elevation"] = ("time", np.asarray(wave_elevation, dtype=float).reshape(-1))
    record = xr.Dataset(data, coords={"time": t, "dof": list(dofs)})
    if heading_deg is not None:
        record.attrs["heading_deg"] = float(heading_deg)
    return validate_record(record)


def time_step(record: xr.Dataset) -> float:
    """The sampling interval of a record, s."""
    t = record.time.values
    return float(t[1] - t[0])


def segments(record: xr.Dataset, length: float, *, overlap: float = 0.0) -> list[xr.Dataset]:
    """Cut a record into consecutive segments of ``length`` seconds (de Haan: blocks of
    "several minutes"), overlapping by ``overlap`` s; a last piece shorter than half a
    segment is dropped. Each segment keeps its absolute times and ``attrs["segment"]``."""
    if not length > 0 or not 0 <= overlap < length:
        raise ValueError("need length > 0 and 0 <= overlap < length")
    dt = time_step(record)
    n = round(length / dt)
    step = max(1, round((length - overlap) / dt))
    total = record.sizes["time"]
    if n > total:
        raise HydroDataError(
            f"the record lasts {total * dt:g} s, shorter than one segment of {length:g} s",
            path=record.attrs.get("source_file"),
        )
    out = []
    for k, start in enumerate(range(0, total, step)):
        stop = min(start + n, total)
        if stop - start < n // 2:
            break
        seg = record.isel(time=slice(start, stop))
        seg.attrs = {**record.attrs, "segment": k}
        out.append(seg)
        if stop == total:
            break
    return out


# --------------------------------------------------------------------------- alignment


@dataclass(frozen=True)
class Alignment:
    """How a predicted signal relates to the measured one: predicted(t) ≈ scale ×
    measured(t − lag).

    Attributes
    ----------
    scale
        γ = RMS(predicted)/RMS(measured) (de Haan (2022) §3.2.1): the prediction is divided by it.
    lag
        s: the prediction runs ``lag`` seconds behind the measurement (a positive lag is
        undone by advancing the prediction).
    correlation
        Pearson correlation of the aligned signals.
    """

    scale: float
    lag: float
    correlation: float


def alignment(predicted: ArrayLike, measured: ArrayLike, dt: float, *, max_lag: float) -> Alignment:
    """Scale and shift of a prediction against a measurement (de Haan (2022) §3.2.1).

    The lag is the one of the largest cross-correlation with |lag| ≤ ``max_lag`` (a bound
    is needed: unrealistic lags sometimes correlate better), refined below one sample by
    a parabola through the peak; the scale is the ratio of RMS values.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.arange(0, 600, 0.5)
    >>> m = np.sin(0.6 * t) + 0.5 * np.sin(1.1 * t + 1)
    >>> p = 3.0 * np.interp(t - 2.0, t, m)
    >>> a = alignment(p, m, 0.5, max_lag=10)
    >>> round(a.scale, 1), round(a.lag, 1)
    (3.0, 2.0)
    """
    from scipy.signal import correlate, correlation_lags

    p = np.asarray(predicted, dtype=float).reshape(-1)
    m = np.asarray(measured, dtype=float).reshape(-1)
    if p.shape != m.shape:
        raise ValueError("predicted and measured need the same length")
    rms_m = float(np.sqrt(np.mean(m**2)))
    rms_p = float(np.sqrt(np.mean(p**2)))
    if rms_m == 0 or rms_p == 0:
        raise HydroDataError("cannot align a signal that is zero throughout")
    pc, mc = p - p.mean(), m - m.mean()
    r = correlate(pc, mc, mode="full", method="fft")
    lags = correlation_lags(p.size, m.size, mode="full")
    # unbiased: divide by the overlap so long lags are not penalised by fewer samples
    r = r / (p.size - np.abs(lags))
    window = np.abs(lags) * dt <= max_lag
    k = int(np.flatnonzero(window)[np.argmax(r[window])])
    shift = float(lags[k])
    if 0 < k < r.size - 1 and window[k - 1] and window[k + 1]:
        y0, y1, y2 = r[k - 1], r[k], r[k + 1]
        denom = y0 - 2 * y1 + y2
        if denom < 0:
            shift += 0.5 * (y0 - y2) / denom
    lag = float(shift * dt)
    scale = rms_p / rms_m
    aligned = shift_signal(p, dt, lag) / scale
    valid = np.isfinite(aligned)
    corr = float(np.corrcoef(aligned[valid], m[valid])[0, 1])
    return Alignment(scale=scale, lag=lag, correlation=corr)


def shift_signal(x: ArrayLike, dt: float, lag: float) -> NDArray[np.float64]:
    """x(t + lag) by linear interpolation (NaN where it falls outside the samples)."""
    x = np.asarray(x, dtype=float)
    t = np.arange(x.shape[0]) * dt
    out = np.full_like(x, np.nan)
    inside = (t + lag >= 0) & (t + lag <= t[-1])
    if x.ndim == 1:
        out[inside] = np.interp(t[inside] + lag, t, x)
    else:
        for j in range(x.shape[1]):
            out[inside, j] = np.interp(t[inside] + lag, t, x[:, j])
    return out


def apply_alignment(record: xr.Dataset, align: Alignment) -> xr.Dataset:
    """The record with its ``excitation_force`` divided by ``align.scale`` and advanced by
    ``align.lag`` (de Haan (2022): one scale and shift, from heave, for all DOFs); the samples
    the shift moves out of the record are cut."""
    if "excitation_force" not in record:
        raise HydroDataError("the record has no excitation_force to align")
    dt = time_step(record)
    force = shift_signal(record.excitation_force.values, dt, align.lag) / align.scale
    keep = np.all(np.isfinite(force), axis=1)
    out = record.copy()
    out["excitation_force"] = (("time", "dof"), force)
    out = out.isel(time=np.flatnonzero(keep))
    out.attrs.update({"force_scale": align.scale, "force_lag": align.lag})
    return out


def excitation_from_elevation(
    ds: xr.Dataset, record: xr.Dataset, heading_deg: float | None = None
) -> xr.Dataset:
    """The record with ``excitation_force`` computed from its ``wave_elevation``.

    τ(t) = F⁻¹[F(ω, β) η̂(ω)], with η̂ the discrete Fourier transform of the elevation at
    the origin (long-crested waves travelling towards ``heading_deg``) and F(ω, β) the
    excitation per metre of wave amplitude of ``ds``
    (:func:`cummins.seakeeping.excitation.excitation_transfer`); zero outside the data's
    frequencies (a warning says how much wave energy lies there). The filter is not
    causal: it suits records analysed after the fact, as model tests are.
    """
    from cummins.hydrodb import single_speed
    from cummins.seakeeping.excitation import excitation_transfer

    if "wave_elevation" not in record:
        raise HydroDataError("the record has no wave_elevation")
    heading = heading_deg if heading_deg is not None else record.attrs.get("heading_deg")
    if heading is None:
        raise HydroDataError(
            "the wave heading is unknown", hint="give heading_deg (--heading on the command line)"
        )
    ds = single_speed(ds)
    eta = record.wave_elevation.values - record.wave_elevation.values.mean()
    dt = time_step(record)
    n = eta.size
    spectrum = np.fft.rfft(eta)
    omega = 2 * np.pi * np.fft.rfftfreq(n, dt)
    w = ds.omega.values
    inside = (omega >= w.min()) & (omega <= w.max())
    energy = np.abs(spectrum) ** 2
    outside = float(energy[~inside].sum() / max(energy.sum(), 1e-300))
    if outside > 0.01:
        warnings.warn(
            f"{outside:.1%} of the wave elevation's variance lies outside the data's "
            f"frequencies ({w.min():.3g}–{w.max():.3g} rad/s): no force is computed there",
            stacklevel=2,
        )
    f = np.zeros((omega.size, ds.sizes["influenced_dof"]), dtype=complex)
    f[inside] = excitation_transfer(ds, omega[inside], np.radians(float(heading)))
    labels = [str(d) for d in ds.influenced_dof.values]
    # x(t) = Re{X e^{iωt}}: rfft holds the e^{+iωt} coefficients, as the convention needs
    force = np.fft.irfft(f * spectrum[:, None], n=n, axis=0)
    dofs = [str(d) for d in record.dof.values]
    missing = [d for d in dofs if d not in labels]
    if missing:
        raise HydroDataError(f"the data have no excitation of {', '.join(missing)}")
    out = record.copy()
    out["excitation_force"] = (("time", "dof"), force[:, [labels.index(d) for d in dofs]])
    out.attrs["heading_deg"] = float(heading)
    return out
