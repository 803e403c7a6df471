"""Check reports: every condition with its status, every violation with a witness."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

HOLDS = "holds"
VIOLATED = "violated"
BY_CONSTRUCTION = "holds by construction"
NOT_APPLICABLE = "not applicable"


@dataclass(frozen=True)
class Violation:
    """One failure of one condition, with the objects that witness it."""

    definition: str
    condition: str
    message: str
    witness: dict[str, Any] = field(default_factory=dict)

    def to_json(self) -> dict[str, Any]:
        return {"definition": self.definition, "condition": self.condition,
                "message": self.message, "witness": self.witness}


@dataclass(frozen=True)
class Check:
    """The outcome of one condition; ``note`` says why when it holds by construction."""

    definition: str
    condition: str
    statement: str
    status: str
    note: str = ""

    def to_json(self) -> dict[str, Any]:
        out = {"definition": self.definition, "condition": self.condition,
               "statement": self.statement, "status": self.status}
        if self.note:
            out["note"] = self.note
        return out


@dataclass(frozen=True)
class Report:
    """All checks of one structure against the definitions for its kind."""

    kind: str
    checks: tuple[Check, ...]
    violations: tuple[Violation, ...]

    @property
    def valid(self) -> bool:
        return not self.violations

    def violated(self, definition: str, condition: str) -> list[Violation]:
        return [v for v in self.violations if v.definition == definition and v.condition == condition]

    def to_json(self) -> dict[str, Any]:
        return {"valid": self.valid, "kind": self.kind,
                "checks": [c.to_json() for c in self.checks],
                "violations": [v.to_json() for v in self.violations]}

    def __add__(self, other: Report) -> Report:
        return Report(self.kind, self.checks + other.checks, self.violations + other.violations)


class ReportBuilder:
    """Collects checks and violations condition by condition."""

    def __init__(self, kind: str, definition: str):
        self.kind = kind
        self.definition = definition
        self.checks: list[Check] = []
        self.violations: list[Violation] = []

    def condition(self, condition: str, statement: str, found: list[Violation], note: str = "") -> None:
        self.violations.extend(found)
        self.checks.append(Check(self.definition, condition, statement, VIOLATED if found else HOLDS, note))

    def given(self, condition: str, statement: str, note: str, status: str = BY_CONSTRUCTION) -> None:
        self.checks.append(Check(self.definition, condition, statement, status, note))

    def violation(self, condition: str, message: str, **witness: Any) -> Violation:
        return Violation(self.definition, condition, message, witness)

    def build(self) -> Report:
        return Report(self.kind, tuple(self.checks), tuple(self.violations))
