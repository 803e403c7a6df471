"""Check reports: every condition with its status, every violation with a witness."""

from __future__ import annotations

from dataclasses import dataclass, field
from enum import StrEnum
from typing import Any


class Status(StrEnum):
    """How one condition came out."""

    HOLDS = "holds"
    VIOLATED = "violated"
    BY_CONSTRUCTION = "holds by construction"
    NOT_APPLICABLE = "not applicable"
    NOT_CHECKED = "not checked"


class Kind(StrEnum):
    """What was checked."""

    POLYCUBE = "polycube"
    LOOP_STRUCTURE = "loop-structure"


class Source(StrEnum):
    """Where a condition comes from: the paper's statements, or the surface and file
    conventions every structure meets first."""

    SURFACE = "surface"
    FILE_CONVENTION = "file convention"
    DEFINITION_1 = "Definition 1"
    DEFINITION_3 = "Definition 3"
    DEFINITION_4 = "Definition 4"
    THEOREM_3 = "Theorem 3"


class Condition(StrEnum):
    """The id of a condition within its :class:`Source`: the paper's numbers, and names for
    the surface and convention checks (``docs/model.md`` lists each with its statement)."""

    ONE = "1"
    TWO = "2"
    THREE = "3"
    FOUR = "4"
    FIVE = "5"
    CLOSED = "closed"
    ORIENTABLE = "orientable"
    MANIFOLD = "manifold"
    CONNECTED = "connected"
    POLYGONS = "polygons"
    QUAD = "quad"
    OUTWARD = "outward"
    ZONE_GENERA = "zone genera"
    X = "X"  # Theorem 3 is checked graph by graph
    Y = "Y"
    Z = "Z"


HOLDS, VIOLATED = Status.HOLDS, Status.VIOLATED
BY_CONSTRUCTION, NOT_APPLICABLE = Status.BY_CONSTRUCTION, Status.NOT_APPLICABLE


@dataclass(frozen=True)
class Violation:
    """One failure of one condition, with the objects that witness it."""

    definition: Source
    condition: Condition
    message: str
    witness: dict[str, Any] = field(default_factory=dict)

    def to_json(self) -> dict[str, Any]:
        """A JSON-ready dict of the violation."""
        return {"definition": str(self.definition), "condition": str(self.condition),
                "message": self.message, "witness": self.witness}


@dataclass(frozen=True)
class Check:
    """The outcome of one condition; ``note`` says why when it holds by construction."""

    definition: Source
    condition: Condition
    statement: str
    status: Status
    note: str = ""

    def to_json(self) -> dict[str, Any]:
        """A JSON-ready dict of the check."""
        out = {"definition": str(self.definition), "condition": str(self.condition),
               "statement": self.statement, "status": str(self.status)}
        if self.note:
            out["note"] = self.note
        return out


@dataclass(frozen=True)
class Report:
    """All checks of one structure against the definitions for its kind."""

    kind: Kind
    checks: tuple[Check, ...]
    violations: tuple[Violation, ...]

    @property
    def valid(self) -> bool:
        """Whether nothing is violated."""
        return not self.violations

    def first_violation(self) -> str:
        """The first violation in one line, with how many more there are (empty when valid)."""
        if not self.violations:
            return ""
        v, n = self.violations[0], len(self.violations)
        more = f" (and {n - 1} more)" if n > 1 else ""
        return f"{v.definition} condition {v.condition}: {v.message}{more}"

    def violated(self, definition: Source | str, condition: Condition | str) -> list[Violation]:
        """The violations of one condition."""
        return [v for v in self.violations if v.definition == definition and v.condition == condition]

    def to_json(self) -> dict[str, Any]:
        """A JSON-ready dict: validity, every check and every violation."""
        return {"valid": self.valid, "kind": str(self.kind),
                "checks": [c.to_json() for c in self.checks],
                "violations": [v.to_json() for v in self.violations]}

    def __add__(self, other: Report) -> Report:
        return Report(self.kind, self.checks + other.checks, self.violations + other.violations)

    def __str__(self) -> str:
        """The verdict, a row per condition in aligned columns, then each violation.

        >>> from polyloops.io.examples import load_example
        >>> from polyloops.verify import verify
        >>> print(str(verify(load_example("double-plus-x"))).splitlines()[0])
        loop-structure: INVALID (4 violations)
        """
        from polyloops.core.words import plural

        verdict = "valid" if self.valid else f"INVALID ({plural(len(self.violations), 'violation')})"
        lines = [f"{self.kind}: {verdict}"]
        names = [f"{c.definition} condition {c.condition}" for c in self.checks]
        width = max(map(len, names), default=0)
        status = max((len(str(c.status)) for c in self.checks), default=0)
        for name, c in zip(names, self.checks, strict=True):
            note = f" ({c.note})" if c.note else ""
            lines.append(f"  {name:<{width}}  {c.status!s:<{status}}  {c.statement}{note}")
        lines += [f"  violation: {v.definition} condition {v.condition}: {v.message}"
                  for v in self.violations]
        return "\n".join(lines)


class ReportBuilder:
    """Collects checks and violations condition by condition."""

    def __init__(self, kind: Kind | str, definition: Source | str):
        self.kind = Kind(kind)
        self.definition = Source(definition)
        self.checks: list[Check] = []
        self.violations: list[Violation] = []

    def condition(self, condition: Condition | str, statement: str, found: list[Violation],
                  note: str = "") -> None:
        """Record a condition that was checked, with what violates it."""
        self.violations.extend(found)
        self.checks.append(Check(self.definition, Condition(condition), statement,
                                 VIOLATED if found else HOLDS, note))

    def given(self, condition: Condition | str, statement: str, note: str,
              status: Status | str = BY_CONSTRUCTION) -> None:
        """Record a condition that holds by construction (or does not apply), with why."""
        self.checks.append(Check(self.definition, Condition(condition), statement, Status(status), note))

    def violation(self, condition: Condition | str, message: str, **witness: Any) -> Violation:
        """A violation of a condition of this builder's source, with its witness."""
        return Violation(self.definition, Condition(condition), message, witness)

    def build(self) -> Report:
        """The report of everything recorded so far."""
        return Report(self.kind, tuple(self.checks), tuple(self.violations))
