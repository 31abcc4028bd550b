"""The result of :func:`cummins.check.check`: a :class:`CheckReport` of findings (:class:`Finding`).

Each finding names its check, a severity (``ok``, ``info``, ``warning``, ``error``), what
was measured, where, and what to do; the report prints as text or JSON.
"""

from __future__ import annotations

import json
from collections.abc import Iterator
from dataclasses import asdict, dataclass, field

SEVERITIES = ("ok", "info", "warning", "error")


@dataclass(frozen=True)
class Finding:
    """One result of a check.

    Attributes
    ----------
    check
        Name of the check (``"symmetry"``, ``"damping_positive"`` …).
    severity
        ``"ok"``, ``"info"``, ``"warning"`` or ``"error"``.
    message
        What was found, in plain language.
    where
        The DOF pair, DOF or frequency concerned, if any.
    value
        The measured number behind the finding (relative, dimensionless), if any.
    advice
        What to do about it, if anything.
    details
        The numbers behind the finding, by name (for ``--json`` users).
    """

    check: str
    severity: str
    message: str
    where: str | None = None
    value: float | None = None
    advice: str | None = None
    details: dict | None = None


@dataclass(frozen=True)
class CheckReport:
    """All findings of :func:`check` on one dataset."""

    source: str
    findings: tuple[Finding, ...] = field(default_factory=tuple)

    def __iter__(self) -> Iterator[Finding]:
        return iter(self.findings)

    def __repr__(self) -> str:  # a notebook's echo: the tally, not every finding's fields
        tally = ", ".join(
            f"{n} {s}" for s in SEVERITIES if (n := sum(f.severity == s for f in self.findings))
        )
        return (
            f"CheckReport({self.source!r}: {len(self.findings)} findings ({tally}), worst "
            f"{self.worst()!r}, ok={self.ok}; print() or .to_text() lists them)"
        )

    def __str__(self) -> str:
        return self.to_text()

    @property
    def ok(self) -> bool:
        """True when no finding is an error."""
        return not any(f.severity == "error" for f in self.findings)

    def worst(self) -> str:
        """The most severe severity present (``"ok"`` if none)."""
        ranks = [SEVERITIES.index(f.severity) for f in self.findings] or [0]
        return SEVERITIES[max(ranks)]

    def by_check(self, name: str) -> list[Finding]:
        """Findings of one check."""
        return [f for f in self.findings if f.check == name]

    def to_dict(self) -> dict:
        """JSON-ready dictionary: ``{"source", "ok", "worst", "findings": [...]}``."""
        return {
            "source": self.source,
            "ok": self.ok,
            "worst": self.worst(),
            "findings": [asdict(f) for f in self.findings],
        }

    def to_json(self, **kwargs) -> str:
        """The report as JSON text."""
        return json.dumps(self.to_dict(), indent=2, **kwargs)

    def to_text(self) -> str:
        """A readable report, one finding per paragraph."""
        marks = {"ok": "ok     ", "info": "info   ", "warning": "WARNING", "error": "ERROR  "}
        lines = [f"Checks of {self.source}"]
        for f in self.findings:
            where = f" [{f.where}]" if f.where else ""
            lines.append(f"  {marks[f.severity]} {f.check}{where}: {f.message}")
            if f.advice:
                lines.append(f"          → {f.advice}")
        lines.append(
            "Result: "
            + ("usable" if self.ok else "NOT usable as it is")
            + f" (worst: {self.worst()})"
        )
        return "\n".join(lines)
