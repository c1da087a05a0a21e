"""The exceptions mechflow raises.

Error is the base of both: ``except mechflow.Error`` catches whatever a
diagram or a run did wrong (a mistake in calling, such as a wrong keyword,
stays a TypeError or ValueError).
"""

import re

# "FILE:LINE: message" (a line number, then ": "); FILE may hold colons
_LOCATION = re.compile(r"^(?P<file>[^\n]+?):(?P<line>\d+): ")


class Error(Exception):
    """Something about a diagram or a run went wrong; see the subclasses."""


class DiagramError(Error):
    """Bad input: a diagram, an identifier, a signal name or an option the
    model refuses, with the same message as the mechflow command prints.

    file, line: where in which file, when the message starts with
    "FILE:LINE: " (None otherwise, e.g. an unknown --set name).
    """

    def __init__(self, message):
        super().__init__(message)
        self.message = message
        found = _LOCATION.match(message)
        self.file = found.group("file") if found else None
        self.line = int(found.group("line")) if found else None


class SimulationError(Error):
    """A run (or an analysis) that failed: the solver could not go on, or a
    block or script refused a value.

    time: the time the run reached [s] (None when no run was under way).
    result: the Result with the rows up to the failure (None when none).
    """

    def __init__(self, message, time=None, result=None):
        super().__init__(message)
        self.message = message
        self.time = time
        self.result = result


class RunInterrupted(KeyboardInterrupt):
    """Ctrl-C during a run: a KeyboardInterrupt that keeps what was computed.

    result: the interrupted run's Result (rows up to its last complete one);
    results: run_many's list, in input order (runs not started have status
    "interrupted" and no rows).
    """

    def __init__(self, message, result=None, results=None):
        super().__init__(message)
        self.result = result
        self.results = results
