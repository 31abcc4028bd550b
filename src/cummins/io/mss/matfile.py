"""The MATLAB side of MSS files: detection and access to the fields of a struct.

:func:`sniff` and :func:`sniff_dir` recognise a MATLAB v5 file holding an MSS ``vessel``
(or ``RAO``) struct; :func:`load_mat_struct` loads a 1×1 struct of a v5–v7 ``.mat`` file
(v7.3/HDF5 is refused with advice), and the private helpers read its fields (numbers,
text, cell arrays) with errors that name the field. Also the two constants of MSS's
vessel layout that reader and writer share (``wamit2vessel.m``, ``vessel2ss.m``).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from cummins.errors import HydroDataError
from cummins.files import note_read

#: The frequency MSS uses as a stand-in for ω = ∞ (``wamit2vessel``, ``vessel2ss``).
MSS_INFINITE_FREQUENCY = 10.0
#: DOF index (0-based) of the three mean drift components MSS stores in ``driftfrc.amp``.
DRIFT_DOFS = (0, 1, 5)


_MAT_MAGIC = b"MATLAB 5.0 MAT-file"
_HDF5_MAGIC = b"\x89HDF\r\n\x1a\n"


# --------------------------------------------------------------------------- detection


def _is_mat_v5(path: Path) -> bool:
    with open(path, "rb") as f:
        head = f.read(128)
    return head.startswith(_MAT_MAGIC)


def sniff(path: Path) -> bool:
    """Content-based test: is ``path`` a MATLAB file holding an MSS ``vessel`` struct?"""
    path = Path(path)
    if not path.is_file() or not _is_mat_v5(path):
        return False
    import scipy.io  # here, not above: sniffing a file of another format need not load it

    try:
        variables = scipy.io.whosmat(str(path))
    except Exception:  # scipy raises many kinds on foreign content
        return False
    return any(name in ("vessel", "RAO") and cls == "struct" for name, _, cls in variables)


def sniff_dir(path: Path) -> list[Path]:
    """The MSS vessel files (``*.mat`` holding a ``vessel`` struct) in a folder."""
    return sorted(p for p in Path(path).glob("*.mat") if sniff(p))


# --------------------------------------------------------------------------- struct access


def load_mat_struct(path: Path, name: str, missing_hint: str) -> np.void:
    """The 1×1 struct ``name`` of a MATLAB (v5–v7) .mat file, or a HydroDataError naming
    the file (v7.3/HDF5, unreadable, no such struct, not a struct)."""
    if not path.is_file():
        raise HydroDataError("file not found", path=path)
    note_read(path)
    with open(path, "rb") as f:
        head = f.read(128)
    if head.startswith(_HDF5_MAGIC) or b"MATLAB 7.3" in head:
        raise HydroDataError(
            "MATLAB v7.3 (HDF5) .mat files are not supported",
            path=path,
            hint=f"in MATLAB, save the struct again with save(file, '{name}', '-v7')",
        )
    try:
        import scipy.io

        content = scipy.io.loadmat(str(path), squeeze_me=False, struct_as_record=True)
    except Exception as exc:  # scipy raises ValueError, TypeError, OSError … on damage
        raise HydroDataError(
            f"not a readable MATLAB .mat file ({exc})",
            path=path,
            hint="check the file was saved by MATLAB (save -v7) and is complete",
        ) from None
    if name not in content:
        names = ", ".join(k for k in content if not k.startswith("__")) or "none"
        raise HydroDataError(
            f"no '{name}' struct in the file (variables: {names})", path=path, hint=missing_hint
        )
    value = content[name]
    if value.dtype.names is None or value.size != 1:
        raise HydroDataError(f"'{name}' is not a 1×1 struct", path=path)
    return value.reshape(-1)[0]


def _has(struct: np.void | None, name: str) -> bool:
    return struct is not None and struct.dtype.names is not None and name in struct.dtype.names


def _field(struct: np.void, name: str, path: Path, owner: str = "vessel") -> Any:
    if not _has(struct, name):
        raise HydroDataError(
            f"the struct has no field {owner}.{name}",
            path=path,
            quantity=f"{owner}.{name}",
            hint="this does not look like a complete MSS vessel struct",
        )
    return struct[name]


def _substruct(struct: np.void, name: str) -> np.void | None:
    if not _has(struct, name):
        return None
    value = struct[name]
    if not isinstance(value, np.ndarray) or value.dtype.names is None or value.size != 1:
        return None
    return value.reshape(-1)[0]


def _numeric(value: Any, path: Path, name: str) -> NDArray[np.float64]:
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise HydroDataError("expected a numeric array", path=path, quantity=name) from None
    return arr


def _scalar(struct: np.void | None, name: str, path: Path, owner: str) -> float | None:
    if not _has(struct, name):
        return None
    arr = _numeric(struct[name], path, f"{owner}.{name}").reshape(-1)
    if arr.size != 1 or not np.isfinite(arr[0]):
        return None
    return float(arr[0])


def _text(struct: np.void | None, name: str) -> str | None:
    if not _has(struct, name):
        return None
    value = np.asarray(struct[name]).reshape(-1)
    if value.size == 1 and isinstance(value[0], str):
        return value[0]
    if value.dtype.kind == "U" and value.size:
        return "".join(str(v) for v in value)
    return None


def _cells(value: Any, path: Path, name: str) -> list[NDArray[np.float64]]:
    """A MATLAB cell array of numeric arrays (``amp{1:6}``) as a list of float arrays."""
    arr = np.asarray(value)
    if arr.dtype != object:
        raise HydroDataError("expected a cell array", path=path, quantity=name)
    return [_numeric(c, path, f"{name}{{{k + 1}}}") for k, c in enumerate(arr.reshape(-1))]
