"""Progress of long runs. The library never prints; this module may: `progress=True` draws a
bar on stderr when stderr is a terminal (nothing otherwise), a callable is called as
progress(fraction, t) with the fraction of the run done (NaN when unknown) and the time."""
import math
import sys
import time


class Bar:
    """A one-line bar on a stream (default stderr): label, percentage, time, elapsed seconds.
    Redrawn at most every `interval` seconds and at the end (fraction 1)."""

    def __init__(self, label="geomint", stream=None, width=30, interval=0.1):
        self.label, self.stream, self.width, self.interval = label, stream or sys.stderr, width, interval
        self.start = time.monotonic()
        self.last = -math.inf
        self.done = False

    def __call__(self, fraction, t):
        now = time.monotonic()
        if self.done or (fraction < 1.0 and now - self.last < self.interval):
            return
        self.last = now
        if math.isnan(fraction):
            text = f"\r{self.label}: t = {t:.6g}, {now - self.start:.1f} s"
        else:
            fill = int(round(fraction * self.width))
            text = (f"\r{self.label} [{'#' * fill}{' ' * (self.width - fill)}] "
                    f"{100 * fraction:5.1f}%  t = {t:.6g}  {now - self.start:.1f} s")
        self.stream.write(text)
        if fraction >= 1.0:
            self.stream.write("\n")
            self.done = True
        self.stream.flush()


def resolve(progress, label):
    """The callable for a `progress=` argument: None/False -> None; True -> a Bar on stderr
    when stderr is a terminal, else None; a callable -> itself."""
    if progress is None or progress is False:
        return None
    if progress is True:
        isatty = getattr(sys.stderr, "isatty", None)
        return Bar(label) if isatty is not None and isatty() else None
    if not callable(progress):
        raise TypeError("progress: expected True, False, None or a callable progress(fraction, t)")
    return progress


def advance_in_chunks(advance, steps, progress, time_of, chunks=200):
    """advance(k) in about `chunks` pieces, calling progress(fraction, time_of()) after each
    (the solvers' advance(a) then advance(b) is advance(a + b): the pieces change nothing)."""
    if progress is None:
        advance(steps)
        return
    progress(0.0, time_of())
    chunk = max(1, steps // chunks)
    done = 0
    while done < steps:
        k = min(chunk, steps - done)
        advance(k)
        done += k
        progress(done / steps, time_of())
    if steps == 0:
        progress(1.0, time_of())
