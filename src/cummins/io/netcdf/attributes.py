"""NetCDF attributes: what cummins' files mark and how attributes NetCDF cannot hold are kept.

NetCDF stores strings, numbers and 1-D numeric arrays as attributes; anything else
(``None``, booleans, dictionaries, complex values, nested lists …) goes, in a tagged JSON
form, into the attribute ``cummins_json_attrs``, so that reading a file cummins wrote gives
back the written attributes exactly. Also the attribute names and time-convention strings
that mark a file written by cummins.
"""

from __future__ import annotations

import json
from typing import Any

import numpy as np

from cummins.errors import HydroDataError

#: Attribute holding, JSON-encoded, the attributes NetCDF cannot store natively.
JSON_ATTRS = "cummins_json_attrs"
#: Attribute marking a file written by cummins (value: the cummins version).
VERSION_ATTR = "cummins_version"
#: Time convention of the numbers stored in the file (Capytaine's).
FILE_TIME_CONVENTION = (
    "x(t) = Re{X exp(-i omega t)} (Capytaine's convention; cummins conjugates on read)"
)
CANONICAL_TIME_CONVENTION = "x(t) = Re{X exp(i omega t)}"


def _python_value(value):
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, bytes):
        return value.decode("utf-8", errors="replace")
    return value


def _is_native(key: Any, value: Any) -> bool:
    """Can NetCDF store this attribute as it is, and give it back unchanged?"""
    if not isinstance(key, str) or not key or key.startswith("_") or key == JSON_ATTRS:
        return False
    if isinstance(value, str):
        return "\x00" not in value
    if isinstance(value, bool | np.bool_):
        return False
    if isinstance(value, int | float | np.integer | np.floating):
        return not isinstance(value, int) or -(2**63) <= value < 2**63
    if isinstance(value, np.ndarray):
        return value.ndim == 1 and value.size >= 2 and value.dtype.kind in "if"
    return False


def encode_attribute(value: Any, key: str) -> Any:
    """Tagged JSON form of an attribute value NetCDF cannot store as it is."""
    if value is None:
        return {"type": "none"}
    if isinstance(value, bool | np.bool_):
        return {"type": "bool", "value": bool(value)}
    if isinstance(value, str):
        return {"type": "str", "value": value}
    if isinstance(value, int | np.integer):
        return {"type": "int", "value": int(value)}
    if isinstance(value, float | np.floating):
        return {"type": "float", "value": float(value)}
    if isinstance(value, complex | np.complexfloating):
        return {"type": "complex", "re": float(value.real), "im": float(value.imag)}
    if isinstance(value, np.ndarray):
        if value.dtype.kind == "c":
            return {
                "type": "ndarray",
                "dtype": value.dtype.str,
                "shape": list(value.shape),
                "re": value.real.reshape(-1).tolist(),
                "im": value.imag.reshape(-1).tolist(),
            }
        if value.dtype.kind not in "biufU":
            raise HydroDataError(f"attribute {key!r}: arrays of {value.dtype} cannot be stored")
        return {
            "type": "ndarray",
            "dtype": value.dtype.str,
            "shape": list(value.shape),
            "data": value.reshape(-1).tolist(),
        }
    if isinstance(value, list | tuple):
        return {"type": type(value).__name__, "items": [encode_attribute(v, key) for v in value]}
    if isinstance(value, dict):
        if not all(isinstance(k, str) for k in value):
            raise HydroDataError(f"attribute {key!r}: dictionary keys must be strings")
        return {"type": "dict", "items": {k: encode_attribute(v, key) for k, v in value.items()}}
    raise HydroDataError(
        f"attribute {key!r} of type {type(value).__name__} cannot be stored in NetCDF",
        hint="convert it to a string, a number or an array before writing",
    )


def decode_attribute(item: dict) -> Any:
    kind = item["type"]
    if kind == "none":
        return None
    if kind in ("bool", "str", "int", "float"):
        return {"bool": bool, "str": str, "int": int, "float": float}[kind](item["value"])
    if kind == "complex":
        return complex(item["re"], item["im"])
    if kind == "ndarray":
        dtype = np.dtype(item["dtype"])
        if "re" in item:
            flat = np.asarray(item["re"], dtype=float) + 1j * np.asarray(item["im"], dtype=float)
        else:
            flat = np.asarray(item["data"])
        return flat.astype(dtype).reshape(item["shape"])
    if kind in ("list", "tuple"):
        items = [decode_attribute(v) for v in item["items"]]
        return items if kind == "list" else tuple(items)
    if kind == "dict":
        return {k: decode_attribute(v) for k, v in item["items"].items()}
    raise ValueError(f"unknown attribute type {kind!r}")


def encode_attributes(attrs: dict) -> dict:
    """Attributes as NetCDF can store them (the rest JSON-encoded in ``cummins_json_attrs``)."""
    native: dict[str, Any] = {}
    special: dict[str, Any] = {}
    for key, value in attrs.items():
        if _is_native(key, value):
            native[key] = str(value) if isinstance(value, np.str_) else value
        else:
            special[str(key)] = encode_attribute(value, str(key))
    if special:
        native[JSON_ATTRS] = json.dumps(special)
    return native


def decode_attributes(attrs: dict, where=None) -> dict:
    """Inverse of :func:`encode_attributes` (NumPy scalars become Python scalars)."""
    out = {k: _python_value(v) for k, v in attrs.items() if k != JSON_ATTRS}
    if JSON_ATTRS in attrs:
        try:
            special = json.loads(str(attrs[JSON_ATTRS]))
            out.update({k: decode_attribute(v) for k, v in special.items()})
        except (ValueError, KeyError, TypeError, AttributeError) as exc:
            raise HydroDataError(
                f"unreadable {JSON_ATTRS} attribute ({exc})",
                path=where,
                hint="the file was edited or damaged",
            ) from None
    return out
