"""How a solve ended, and the exceptions for a solve or a run that did not succeed."""

from dataclasses import dataclass

from ._fairshape import Error


@dataclass(frozen=True)
class Summary:
    """What every fairshape solve reports.

    termination: 'converged', 'energy_stalled', 'schedule_completed' (successes) or a failure
    ('max_iterations', 'constraints_unmet', 'ill_conditioned', 'numerical_failure', ...);
    iterations: iterations made (0 for a direct solve); residual: relative ‖b − Ax‖/‖b‖
    (−1: not measured); message: fairshape's explanation of a failure ('' otherwise).
    """

    termination: str
    iterations: int
    residual: float
    message: str
    succeeded: bool

    @classmethod
    def from_dict(cls, d):
        return cls(d["termination"], d["iterations"], d["residual"], d["message"], d["succeeded"])


class SolveFailed(Error):
    """A solve ended without success (check=True). .result holds what it returned."""

    def __init__(self, message, result):
        super().__init__(message)
        self.result = result


class RunFailed(Error):
    """`fairshape.run` finished but some run failed (the CLI's exit 3). .runs is the DataFrame."""

    def __init__(self, message, runs):
        super().__init__(message)
        self.runs = runs


for _cls in (Summary, SolveFailed, RunFailed):
    _cls.__module__ = "fairshape"
