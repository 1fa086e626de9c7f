"""Counts of rejected messages by cause, each cause logged once (at its first rejection)."""

import logging
import threading


class Rejections:
    """Thread-safe counts of rejected messages, by cause; the first of each cause is logged."""

    def __init__(self, log: logging.Logger):
        self._log = log
        self._lock = threading.Lock()
        self._counts: dict[str, int] = {}

    def reject(self, cause: str, detail: str) -> None:
        """Counts one message rejected for ``cause``; logs it if it is the first of its cause."""
        with self._lock:
            first = cause not in self._counts
            self._counts[cause] = self._counts.get(cause, 0) + 1
        if first:
            self._log.warning("rejected (%s, logged once per cause): %s", cause, detail[:200])

    def counts(self) -> dict[str, int]:
        """A copy of the counts."""
        with self._lock:
            return dict(sorted(self._counts.items()))
