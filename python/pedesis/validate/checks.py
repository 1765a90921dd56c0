"""What a validation case reports: checks of a measured value against a reference."""
from dataclasses import dataclass, field
from typing import Callable, Optional


class CaseError(Exception):
    """A case could not measure: its run failed or wrote less than the case needs."""


@dataclass
class Check:
    """One measured value against its reference.

    It passes when ``lower <= measured <= upper`` and, where ``max_error`` is set, the
    statistical error is below it: a run too short for its tolerance never passes by luck.
    ``why`` says why the tolerance is fair for the run length."""

    quantity: str
    measured: float
    error: float
    reference: str
    source: str
    lower: float
    upper: float
    why: str
    max_error: Optional[float] = None

    @classmethod
    def near(cls, quantity, measured, error, reference, tolerance, source, why, unit=""):
        """A check of |measured - reference| <= tolerance with error <= tolerance / 3."""
        return cls(quantity, measured, error, f"{reference:.5g}{unit} ± {tolerance:.2g}", source,
                   reference - tolerance, reference + tolerance, why, tolerance / 3.0)

    @property
    def passed(self):
        inside = self.lower <= self.measured <= self.upper
        precise = self.max_error is None or self.error <= self.max_error
        return bool(inside and precise)

    @property
    def verdict(self):
        if self.passed:
            return "pass"
        if self.max_error is not None and self.error > self.max_error:
            return "FAIL (run too short: error above a third of the tolerance)"
        return "FAIL"


@dataclass
class CaseResult:
    """A case's checks, a line on what it ran, and a function drawing its figure on a
    matplotlib Axes (or None)."""

    name: str
    title: str
    ran: str
    checks: list = field(default_factory=list)
    plot: Optional[Callable] = None
    error: Optional[str] = None

    @property
    def passed(self):
        return self.error is None and all(c.passed for c in self.checks)
