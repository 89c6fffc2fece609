# SPDX-License-Identifier: LGPL-2.1-or-later
"""How the long computations (``decompose()``, ``slice()``) report how far they are, and how they
are stopped.

``progress``, the keyword they take, is None or a callable ``progress(fraction, stage)``: called
now and then, from the calling thread, with the fraction of the whole done so far (0 to 1, never
decreasing; 1 when done) and the stage in words ("slicing component 2 (3 of 5)"). To stop the
work it raises: ``Cancelled`` by convention, or any exception, which the computation raises again
unchanged. Nothing the caller passed is modified by a stopped computation. Python's signal
handlers run at the engine's reports too, with or without a callback: Ctrl-C stops the work with
``KeyboardInterrupt`` at the next report (every few milliseconds while slicing; OCCT's Booleans
run to their end, so decomposing may take up to about half a second)::

    def progress(fraction, stage):
        print("{:4.0%} {}".format(fraction, stage))
        if user_wants_to_stop():
            raise MultiAxisSlicer.Cancelled("slicing cancelled")
    result = MultiAxisSlicer.slice(shape, progress=progress)

Document objects (``MultiAxisSlicer.features``) report their recomputes through ``reporting()``:
the GUI installs a reporter (a progress dialog with a Cancel button) with ``set_reporter()``;
without one (freecadcmd, scripts) nothing is reported.
"""

import contextlib


class Cancelled(Exception):
    """The user (or a script's progress callback) stopped a long computation."""


def check(progress):
    """``progress`` if it is None or callable; TypeError naming it otherwise."""
    if progress is not None and not callable(progress):
        raise TypeError("progress must be None or callable as progress(fraction, stage), got "
                        "{!r}".format(progress))
    return progress


def span(progress, lo, hi):
    """A callback reporting [0, 1] of a stage as [lo, hi] of ``progress``; None for None."""
    if progress is None:
        return None

    def report(fraction, stage):
        progress(lo + (hi - lo) * min(max(fraction, 0.0), 1.0), stage)

    return report


_reporter = None


def set_reporter(reporter):
    """Installs ``reporter(title)``, a context manager factory yielding a progress callback (or
    None), through which document objects report their recomputes; None removes it. Returns the
    one installed before."""
    global _reporter
    previous, _reporter = _reporter, reporter
    return previous


@contextlib.contextmanager
def reporting(title):
    """A progress callback for a computation named ``title`` ("Slicing 'Layers'"), from the
    installed reporter; None without one."""
    if _reporter is None:
        yield None
    else:
        with _reporter(title) as progress:
            yield progress
