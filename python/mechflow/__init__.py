"""mechflow: simulate dataflow diagrams with multibody mechanisms from Python.

    import mechflow
    d = mechflow.load("diagrams/examples/damping_ratio.xml")
    r = d.run(t_end=5, set={"beta": 0.1})
    r["m.x"], r.time, r.to_pandas()
    results = d.run_many([{"set": {"beta": b}} for b in (0.05, 0.1, 0.2)], threads=2)

The diagram is read once (load); every run builds its model anew from what
was read, so its rows equal `mechflow run`'s bit for bit. Errors are
DiagramError (bad input, with file and line) and SimulationError (a failed
run, with the time and the rows up to it); both subclass Error. Ctrl-C
during a run ends it at its last row and raises KeyboardInterrupt.
"""

import collections
import collections.abc
import numbers
import os
import threading

import numpy as np

from . import _mechflow
from ._errors import DiagramError, Error, RunInterrupted, SimulationError
from ._result import Event, Figure, Result

__all__ = ["load", "psd", "Diagram", "Result", "Modes", "Spectrum", "ForceAnalysis", "Identifier", "Figure",
           "Event", "Error", "DiagramError", "SimulationError", "RunInterrupted"]
__version__ = "0.1.0"

Identifier = collections.namedtuple("Identifier", "name value unit comment derived si_value")
Identifier.__doc__ = """An identifier of a diagram: its name, its value in its unit
(the unit its definition is written in; "" none), its comment, whether it is
derived (defined by an expression of other identifiers; set= refuses it) and
its value in SI units."""


def _on_main_thread():
    # Python's signal handlers belong to the main thread: only there may a run
    # take over SIGINT for its duration
    return threading.current_thread() is threading.main_thread()


def _paths(value, what):
    if value is None:
        return []
    if isinstance(value, (str, os.PathLike)):
        return [os.fspath(value)]
    return [os.fspath(v) for v in value]


def load(path, variant=None, set=None, library=(), allow_read=(), unsafe_lua=False):
    """Reads, checks and builds the diagram file `path` once; returns a Diagram.

    variant: a variant name or a list of them (as --variant, applied in order).
    set: {identifier: value}, as --set NAME=VALUE: a number in the unit of the
        identifier's definition, or a text holding an expression of other
        identifiers (--set NAME=EXPR). These hold for every run of the diagram.
    library: folders subsystem and part files are looked up in (--library).
    allow_read: folders the files the diagram names may also be read from
        (--allow-read); by default only its own folder's tree.
    unsafe_lua: Lua without the sandbox (--unsafe-lua).

    The Lua sandbox and the limits are the command line's. Raises
    DiagramError (with .file and .line) for bad input.
    """
    return Diagram(path, variant=variant, set=set, library=library, allow_read=allow_read, unsafe_lua=unsafe_lua)


class Diagram:
    """A diagram file read once, to be run as often as wanted (see load)."""

    def __init__(self, path, variant=None, set=None, library=(), allow_read=(), unsafe_lua=False):
        variants = [variant] if isinstance(variant, str) else list(variant or [])
        self._model = _mechflow.Model(os.fspath(path), variants, set or {}, _paths(library, "library"),
                                      _paths(allow_read, "allow_read"), bool(unsafe_lua))

    @property
    def path(self):
        """The file it was read from."""
        return self._model.path

    @property
    def name(self):
        """The diagram's name (<diagram name=...>, else the file's stem)."""
        return self._model.name

    @property
    def identifiers(self):
        """The identifiers as they stand (after variant= and set= of load), a
        list of Identifier(name, value, unit, comment, derived, si_value)."""
        return [Identifier(*i) for i in self._model.identifiers()]

    @property
    def signals(self):
        """Every signal a run can log ("block.port"), in block order; log= takes
        these (and "block.port[i]" for one element of a wider one)."""
        return self._model.signals()

    @property
    def warnings(self):
        """What the loader warned of ("file:line: warning: ...", e.g. units that disagree)."""
        return self._model.warnings()

    def check(self):
        """What `mechflow check` prints, as data: a dict with the counts (blocks,
        connections, num_states, num_zero_crossings), identifiers, variants,
        schedule (the evaluation order: output ports and algebraic loops),
        algebraic_loops (through, tears, unknowns, tolerance), states (x[i]'s
        names), jacobian ("analytic" or "difference quotients", and
        jacobian_why), zero_crossings, sampled_blocks, control_script, solver
        (t_start, t_end, rtol, atol, interval), logged_columns, instances and
        warnings."""
        return self._model.check()

    def run(self, t_end=None, set=None, log=None, interval=None, rtol=None, atol=None, times=None):
        """Runs the diagram once; returns its Result (rows in memory, no files).

        t_end, interval, rtol, atol: as --t-end, --interval, --rtol, --atol.
        set: {identifier: value} for this run only (after load's set=).
        log: the signals to log ("block.port", "block.port[i]"), each a
            column under that name in the signal's own unit (SI); by default
            the diagram's <log>s with their labels and units.
        times: rows at exactly these instants [s] instead of every interval
            (increasing, within the run; not together with interval): no
            row at the start unless it is one of them.

        Raises DiagramError for bad input, SimulationError (with .time and
        .result, the rows up to the failure) when the run fails, and
        RunInterrupted (a KeyboardInterrupt, with .result) on Ctrl-C. A run
        its control script stops returns normally, with status "stopped".
        """
        raw = self._model.run(_run_keywords(t_end, set, log, interval, rtol, atol, times), _on_main_thread())
        result = _many_result(raw)
        if raw["error_kind"]:  # refused before it ran: the error alone
            raise result.error
        if result.status == "interrupted":
            raise RunInterrupted(f"run interrupted at t = {result.t_reached:g} s", result=result)
        if result.status == "failed":
            raise SimulationError(f"simulation failed at t = {result.t_reached:g} s: {result.reason}",
                                  time=result.t_reached, result=result)
        return result

    def run_many(self, runs, threads=None):
        """Runs each dict of run() keywords in `runs` on `threads` C++ threads
        (default: the processors there are), without holding the GIL; returns
        their Results in input order, each equal bit for bit to what run()
        gives for the same keywords.

        A run that fails does not stop the others: its Result has status
        "failed" and .error, the exception run() would have raised
        (DiagramError, SimulationError). Ctrl-C ends the runs under way at
        their last row and starts no more; RunInterrupted is raised then,
        with every Result in .results.
        """
        requests = []
        for index, keywords in enumerate(runs):
            if not isinstance(keywords, collections.abc.Mapping):
                raise TypeError(f"run_many: run {index} is a {type(keywords).__name__}, not a dict of run() keywords")
            unknown = set_difference(keywords, _RUN_KEYWORDS)
            if unknown:
                raise TypeError(f"run_many: run {index}: unknown keyword {unknown[0]!r} "
                                f"(run() takes {', '.join(_RUN_KEYWORDS)})")
            try:
                requests.append(_run_keywords(**keywords))
            except (TypeError, ValueError) as e:
                raise type(e)(f"run_many: run {index}: {e}") from None
        threads = (os.cpu_count() or 1) if threads is None else int(threads)
        results = [_many_result(raw) for raw in self._model.run_many(requests, threads, _on_main_thread())]
        if any(r.status == "interrupted" for r in results):
            done = sum(r.status != "interrupted" for r in results)
            raise RunInterrupted(f"run_many interrupted: {done} of {len(results)} runs finished", results=results)
        return results

    def modes(self, equilibrium=False, set=None):
        """The linear analysis of `mechflow modes`: the diagram linearised at its
        initial state, or (equilibrium=True) at the static equilibrium found
        from it; returns Modes (numpy arrays: frequencies, damping ratios,
        eigenvalues, shapes). set: {identifier: value} for this analysis only.
        Raises DiagramError when the diagram has no continuous states,
        SimulationError when no equilibrium is found."""
        return Modes(self._model.modes(bool(equilibrium), set or {}))

    def force_analysis(self, element, amplitude, frequency, component=None, cycles=10, samples=1000, vary=None,
                       set=None):
        """`mechflow force-analysis`: the force element `element`, detached and
        driven as x = x0 + a sin(2 pi f t) for every amplitude a and frequency f
        (numbers or lists), `cycles` periods of `samples` rows each; returns
        ForceAnalysis (arrays per case: stiffness K = |R1|/a, phase [rad],
        force amplitude, loop energy [J], periodic, and the last period's
        loop). component: a bushing's dx ... az. vary: {identifier or tuple of
        identifiers: values}, every combination run. Ctrl-C raises
        KeyboardInterrupt."""
        kwargs = dict(element=element, amplitude=amplitude, frequency=frequency, component=component,
                      cycles=int(cycles), samples=int(samples), vary=vary or {}, set=set or {})
        return ForceAnalysis(self._model.force_analysis(kwargs, _on_main_thread()))

    def __repr__(self):
        return f"<mechflow.Diagram {self.name!r} from {self.path!r}>"


_RUN_KEYWORDS = ("t_end", "set", "log", "interval", "rtol", "atol", "times")


def set_difference(keywords, allowed):
    return [k for k in keywords if k not in allowed]


def _number(name, value):
    if value is None or (isinstance(value, numbers.Real) and not isinstance(value, bool)):
        return value
    raise TypeError(f"{name} must be a number, not {type(value).__name__} {value!r}")


def _run_keywords(t_end=None, set=None, log=None, interval=None, rtol=None, atol=None, times=None):
    if set is not None and not isinstance(set, collections.abc.Mapping):
        raise TypeError(f"set must be a dict {{identifier: value}}, not {type(set).__name__}")
    if isinstance(log, str):
        log = [log]
    if log is not None and not all(isinstance(name, str) for name in log):
        raise TypeError(f"log must be a list of signal names (\"block.port\"), not {log!r}")
    if times is not None:
        try:
            times = [float(t) for t in np.asarray(times, dtype=float).ravel()]
        except (TypeError, ValueError):
            raise TypeError(f"times must be numbers [s], not {times!r}") from None
        if not times:
            raise ValueError("times is empty: give the instants wanted, or leave times out for a row every interval")
    return {"t_end": _number("t_end", t_end), "set": set or {}, "log": log, "interval": _number("interval", interval),
            "rtol": _number("rtol", rtol), "atol": _number("atol", atol), "times": times}


def _many_result(raw):
    if raw["error_kind"] == "DiagramError":
        return Result(raw, error=DiagramError(raw["error"]))
    if raw["error_kind"] == "SimulationError":
        return Result(raw, error=SimulationError(raw["error"]))
    if raw["error_kind"] == "Error":
        return Result(raw, error=Error(raw["error"]))
    result = Result(raw)
    if result.status == "failed":
        result.error = SimulationError(f"simulation failed at t = {result.t_reached:g} s: {result.reason}",
                                       time=result.t_reached, result=result)
    return result


class Modes:
    """A linear analysis (Diagram.modes), modes sorted by natural frequency.

    frequency            damped frequency |Im lambda| / 2 pi [Hz]
    natural_frequency    |lambda| / 2 pi [Hz]
    damping_ratio        -Re lambda / |lambda|
    eigenvalues          lambda [rad/s] (complex)
    decay_rate           -Re lambda [1/s]
    kinds                "oscillating", "decaying", "growing", "rigid-body"
    shapes               states x modes: the real part of each eigenvector,
                         scaled so its largest coordinate is 1
    states               the states' names ("block.state"); x their values
    coordinate, rate     per state, its role
    equilibrium          None, or {iterations, residual, rounds, switched}
    switching            what the switching elements were taken as
    time                 where it was linearised [s]
    """

    def __init__(self, raw):
        self.__dict__.update(raw)
        self.coordinate = np.array(raw["coordinate"], dtype=bool)
        self.rate = np.array(raw["rate"], dtype=bool)

    def __len__(self):
        return len(self.frequency)

    def __repr__(self):
        shown = ", ".join(f"{f:.4g}" for f in self.natural_frequency[:5]) + (" ..." if len(self) > 5 else "")
        return f"<mechflow.Modes {len(self)} modes of {len(self.states)} states; f natural [Hz]: {shown}>"


class Spectrum:
    """A power spectral density (psd): frequency [Hz], density [signal^2/Hz],
    segment (samples per segment), segments, resolution [Hz], and the peaks
    strongest first: peak_frequency [Hz], peak_level."""

    def __init__(self, raw):
        self.__dict__.update(raw)

    def __repr__(self):
        peaks = ", ".join(f"{f:.6g} Hz" for f in self.peak_frequency[:3])
        return (f"<mechflow.Spectrum {len(self.frequency)} bins of {self.resolution:.4g} Hz, "
                f"{self.segments} segments; peaks: {peaks}>")


class ForceAnalysis:
    """A force analysis (Diagram.force_analysis), one entry per case (varied
    values, then amplitude, then frequency fastest): amplitude, frequency
    [Hz], stiffness K, phase delta [rad], force_amplitude, loop_energy, x0,
    periodic (bool), periodic_error, failure ("" when it ran), varied (cases
    x vary), and loops: per case {x, v, reaction} over the last period."""

    def __init__(self, raw):
        self.__dict__.update(raw)
        self.periodic = np.array(raw["periodic"], dtype=bool)

    def __len__(self):
        return len(self.amplitude)

    def __repr__(self):
        return f"<mechflow.ForceAnalysis of {self.element} in {self.diagram!r}: {len(self)} cases>"


def psd(samples, dt, segment=0, overlap=0.5, window="hann", peaks=5):
    """The power spectral density of evenly spaced `samples` (interval dt [s])
    by Welch's method, as `mechflow psd` computes it: the mean removed,
    segments of `segment` samples (0: the largest power of two up to a quarter
    of them) overlapping by `overlap`, each windowed ("hann" or
    "rectangular") and transformed; one-sided, in signal^2/Hz. Returns a
    Spectrum with the `peaks` strongest peaks. Raises DiagramError for bad
    options or too few samples."""
    return Spectrum(_mechflow.psd(np.asarray(samples, dtype=float), float(dt), int(segment), float(overlap),
                                  str(window), int(peaks), _on_main_thread()))
