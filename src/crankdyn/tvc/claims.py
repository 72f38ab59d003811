"""Which of a calculation's conditions each of two processes computes (core).

The TVC's conditions (one resolved forced response each; six or so misfiring cylinders among
them) are shared between the process that runs them and the child beside it that runs the
transient events (:func:`crankdyn.tvc.analysis.tvc`): this process takes them from the start
of the list, the child from its end once its events are done, each claiming one at a time, so
that both end together whatever the events cost. The two ends are kept in memory shared
across the fork (:class:`multiprocessing.Array`, its lock a semaphore); each condition is
claimed by exactly one side. Where there is no child the first side claims every one; where a
child failed part way (:class:`crankdyn.forks.Beside` then computes its function here),
:meth:`Claims.unjudged` gives the conditions it had claimed, so that every one is computed
once in the results.
"""

from __future__ import annotations

import contextlib
import multiprocessing
from collections.abc import Container, Iterable
from typing import Any

__all__ = ["Claims"]


class _Local(list):
    """The two ends in this process only, with the interface of a shared array."""

    def get_lock(self) -> contextlib.nullcontext[None]:
        return contextlib.nullcontext()


class Claims:
    """A list of indices claimed one at a time from either end (module docstring).

    Parameters
    ----------
    indices : iterable of int
        What is to be claimed, in order.

    Examples
    --------
    >>> claims = Claims([3, 4, 5, 6])
    >>> claims.front(), claims.back(), claims.front(), claims.back(), claims.front()
    (3, 6, 4, 5, None)
    >>> claims.unjudged({6: "done"})
    5
    """

    def __init__(self, indices: Iterable[int]) -> None:
        self.indices = tuple(int(i) for i in indices)
        # the next index from the start, one past the next from the end
        ends = [0, len(self.indices)]
        try:
            self._ends: Any = multiprocessing.Array("q", ends)
            self.shared = True
        except OSError:  # no shared memory or semaphores here (some sandboxes): this process's
            self._ends, self.shared = _Local(ends), False

    shared: bool
    """Whether the claims are shared with a child forked from this process (else a child must
    not be started: it would compute every condition again)."""

    @property
    def size(self) -> int:
        """How many indices there are (claimed or not)."""
        return len(self.indices)

    def front(self) -> int | None:
        """Claim the next index from the start.

        Returns
        -------
        int or None
            The index, or None when every one is claimed.
        """
        return self._claim(0)

    def back(self) -> int | None:
        """Claim the next index from the end.

        Returns
        -------
        int or None
            The index, or None when every one is claimed.
        """
        return self._claim(1)

    def _claim(self, side: int) -> int | None:
        """Move end ``side`` (0: the start, 1: the end) one index inwards, and return the index
        it passed; None when the ends have met."""
        with self._ends.get_lock():
            start, end = self._ends[0], self._ends[1]
            if start >= end:
                return None
            at = start if side == 0 else end - 1
            self._ends[side] = start + 1 if side == 0 else end - 1
            return self.indices[at]

    def unjudged(self, judged: Container[int]) -> int | None:
        """The first index claimed from the end that is not in ``judged`` (claimed by a child
        that failed before its results came back).

        Parameters
        ----------
        judged : container of int
            The indices whose results are in hand.

        Returns
        -------
        int or None
            The index, or None when every index claimed from the end is in ``judged``.
        """
        with self._ends.get_lock():
            end = self._ends[1]
        return next((i for i in reversed(self.indices[end:]) if i not in judged), None)
