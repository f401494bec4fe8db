"""Progress on long work: a one-line bar on stderr when it is a terminal."""
from __future__ import annotations


class progress_bar:
    """A one-line progress bar on stderr when it is a terminal (a no-op otherwise)."""

    def __init__(self, label: str):
        import sys
        self.label = label
        self.stream = sys.stderr
        self.on = self.stream.isatty()
        self.shown = False

    def __call__(self, fraction: float) -> None:
        if not self.on:
            return
        n = int(round(30 * min(max(fraction, 0.0), 1.0)))
        self.stream.write(f"\r{self.label} [{'#' * n}{'.' * (30 - n)}] {100 * fraction:5.1f} %")
        self.stream.flush()
        self.shown = True

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        if self.shown:
            self.stream.write("\r" + " " * (len(self.label) + 42) + "\r")
            self.stream.flush()
        return False
