"""How far a fit has got: model evaluations counted, the ones left estimated.

A fit is a known sequence of stages (each multistart start, the Jacobian, each free parameter's
profile walk, each data set's separate fit for the consistency test) of unknown length each: an
optimiser stops when it converges. :class:`EvaluationTracker` counts the evaluations of the
model (each one a simulation for the trap model on a time series, 0.1-1 s) and estimates those
left as the stages still to run times the mean cost of the finished stages of their kind, so
the estimate, and an ETA drawn from it, improves as the fit goes.
"""

from __future__ import annotations

from collections.abc import Callable

__all__ = ["FitProgress", "EvaluationTracker", "PROFILE_COST"]

FitProgress = Callable[[int, int, str], None]
"""``progress(done, total, what)``: model evaluations done, an estimate of the evaluations in
all (it changes as the stages finish), and the stage running (``start 2 of 3``)."""

PROFILE_COST = 10.0
"""Before any profile has finished: the profiles of all free parameters together are taken to
cost this many times the starts (the measured "about ten" for the trap model,
docs/tutorials/lab-record.md)."""


class EvaluationTracker:
    """Counts a fit's model evaluations by stage and estimates the total.

    Parameters
    ----------
    p : int
        Free parameters (the Jacobian costs ``2 p`` evaluations).
    stages : dict
        Stage kind -> how many of them the fit will run: ``start``, ``jacobian``,
        ``profile``, ``consistency``.
    report : callable, optional
        :data:`FitProgress`, called after every evaluation.
    """

    def __init__(self, p: int, stages: dict[str, int], report: FitProgress | None) -> None:
        self.p = p
        self.report = report
        self.left = dict(stages)
        self.n_starts = stages.get("start", 1)
        self.used: dict[str, list[int]] = {k: [] for k in stages}
        self.done = 0
        self.kind, self.what, self.stage0 = "", "", 0

    def begin(self, kind: str, what: str) -> None:
        """A stage of ``kind`` starts (``what`` is shown)."""
        self.kind, self.what, self.stage0 = kind, what, self.done
        self.left.setdefault(kind, 1)
        self.used.setdefault(kind, [])

    def end(self) -> None:
        """The running stage finished."""
        if self.kind:
            self.used[self.kind].append(self.done - self.stage0)
            self.left[self.kind] = max(self.left[self.kind] - 1, 0)
        self.kind = ""

    def add(self, kind: str, n: int = 1) -> None:
        """``n`` more stages of ``kind`` than planned (a profile restarted the fit)."""
        self.left[kind] = self.left.get(kind, 0) + n
        self.used.setdefault(kind, [])

    def per_stage(self, kind: str) -> float:
        """Evaluations one stage of ``kind`` is expected to take."""
        if self.used.get(kind):
            return sum(self.used[kind]) / len(self.used[kind])
        start = (sum(self.used["start"]) / len(self.used["start"]) if self.used.get("start")
                 else 10.0 * (self.p + 1))  # about ten iterations of a forward-difference step
        if kind == "jacobian":
            return 2.0 * self.p
        if kind == "profile":
            return PROFILE_COST * self.n_starts * start / max(self.p, 1)
        return start  # a start, or a data set's separate fit

    def total(self) -> int:
        """Evaluations done plus the estimate of those left (at least one while a stage
        runs)."""
        rest = 0.0
        for kind, n in self.left.items():
            if n <= 0:
                continue
            per = self.per_stage(kind)
            if kind == self.kind:
                rest += max(per - (self.done - self.stage0), 1.0) + per * (n - 1)
            else:
                rest += per * n
        return self.done + round(rest)

    def tick(self) -> None:
        """One evaluation done."""
        self.done += 1
        if self.report is not None:
            self.report(self.done, self.total(), self.what)

    def nested(self) -> FitProgress:
        """A ``progress`` for a fit run inside this one (a data set fitted alone): each of its
        evaluations is one here, its final report (no evaluation) none."""
        seen = [0]

        def report(done: int, total: int, what: str) -> None:
            while seen[0] < done:
                seen[0] += 1
                self.tick()

        return report
