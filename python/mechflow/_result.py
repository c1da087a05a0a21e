"""Result: one run's rows, in memory, with what the run reported."""

import collections
import difflib

import numpy as np

Figure = collections.namedtuple("Figure", "label kind signal value unit time found")
Figure.__doc__ = """A <report> figure: its label, kind ("peak", "rms", ...), the
signal it watched, its value (in unit) and the time it occurred [s]; found is
False when the run took no step (value and time are then NaN)."""

Event = collections.namedtuple("Event", "time name block crossing direction")
Event.__doc__ = """A zero-crossing event: its time [s], what it was (as
`mechflow run --verbose` names it), the block's index, the block's own crossing
number and its direction (+1 rising, -1 falling)."""


class Result:
    """The rows of one run and what the run reported.

    r.time                 the times of the rows [s] (a numpy array)
    r["m.x"]               a column by its name in the results CSV's header
    r.columns              the column names, "time" first
    r.units                {column: unit} ("" when unknown)
    r.to_numpy()           a structured array, one field per column
    r.to_pandas()          a DataFrame indexed by time
    r.status               "ok", "stopped" (by the control script), "failed",
                           "interrupted"
    r.reason               why it stopped, failed or was interrupted ("" if ok)
    r.t_reached            the time the run reached [s]
    r.figures              the <report> figures (Figure tuples)
    r.events               the zero-crossing events (Event tuples)
    r.stats                the solver's counters (steps, rhs_evaluations, ...) and
                           wall_seconds, the simulation's own time
    r.error                for a run of run_many that failed: its exception
                           (DiagramError, SimulationError), else None
    """

    def __init__(self, raw, error=None):
        self._names = list(raw["columns"])
        self._data = dict(zip(self._names, raw["data"]))
        self.units = dict(zip(self._names, raw["units"]))
        self.status = raw["status"]
        self.reason = raw["reason"]
        self.t_reached = raw["t_reached"]
        self.stats = dict(raw["stats"])
        self.figures = [Figure(f["label"], f["kind"], f["signal"], f["value"], f["unit"], f["time"], f["found"])
                        for f in raw["figures"]]
        self.events = [Event(e["time"], e["name"], e["block"], e["crossing"], e["direction"])
                       for e in raw["events"]]
        self.error = error

    @property
    def ok(self):
        """True when the run reached its end or its control script stopped it."""
        return self.status in ("ok", "stopped")

    @property
    def columns(self):
        """The column names, "time" first, as the results CSV's header has them."""
        return list(self._names)

    @property
    def time(self):
        """The times of the rows [s]."""
        return self._data["time"] if "time" in self._data else np.empty(0)

    def __len__(self):
        return len(self.time)

    def __contains__(self, name):
        return name in self._data

    def __getitem__(self, name):
        """The column `name` (a numpy array); KeyError naming the nearest names."""
        try:
            return self._data[name]
        except KeyError:
            near = difflib.get_close_matches(name, self._names, n=3, cutoff=0.5)
            hint = f"; did you mean {', '.join(near)}?" if near else ""
            if "." in name:  # a signal whose <log> gave its column a label of its own
                hint += f" (a <log> label names its column; run(log=[{name!r}]) gives a signal under its own name)"
            raise KeyError(f"no column {name!r}{hint} (columns: {', '.join(self._names)})") from None

    def to_numpy(self):
        """The rows as a structured numpy array: one float64 field per column,
        named as the columns are ("time" first)."""
        array = np.empty(len(self), dtype=[(name, np.float64) for name in self._names])
        for name in self._names:
            array[name] = self._data[name]
        return array

    def to_pandas(self):
        """The rows as a pandas DataFrame: the columns but time, indexed by time."""
        try:
            import pandas
        except ImportError as e:
            raise ImportError("Result.to_pandas needs pandas (Debian: apt install python3-pandas; "
                              "pip: pip install pandas); to_numpy() needs only numpy") from e
        frame = pandas.DataFrame({name: self._data[name] for name in self._names if name != "time"},
                                 index=pandas.Index(self.time, name="time"))
        frame.attrs["units"] = dict(self.units)
        return frame

    def __repr__(self):
        shown = ", ".join(self._names[1:6]) + (", ..." if len(self._names) > 6 else "")
        end = f"t = {self.t_reached:g} s" if self.t_reached is not None else "not run"
        why = f" ({self.reason})" if self.reason and self.status != "ok" else ""
        return f"<mechflow.Result {self.status}{why}, {end}, {len(self)} rows: {shown}>"
