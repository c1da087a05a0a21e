#!/usr/bin/env python3
"""What a run through the Python module costs, as ratios measured in one go.

P1 (the seed ElastFriction, variant Free: a box sliding to rest on a
frictional element, 3 s, its 1 ms output grid: 3001 rows):

1. a run through the module with its rows in memory against the simulator's
   own time for the same run (RunResult's wall time around the simulation
   alone): the module's overhead per run (building the run from the kept
   description, handing rows to numpy);
2. run_many of RUNS runs on 2 threads against 1 thread, the best of ROUNDS
   alternating rounds (and each round's own ratio), beside the same runs in
   two processes of one thread against one: what this machine gives two
   cores while the bench runs (the two cores of a virtual machine slow each
   other from one moment to the next, whatever runs on them: a plain C loop
   over 16 KB of memory by up to 40 %);
3. a loop of RUNS runs in Python against RUNS `mechflow run` processes
   (--no-plot, results to a file, as a script calling the command would).

    PYTHONPATH=build/python /usr/bin/python3 bench/python_module.py [build] [RUNS]
"""

import os
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time

import mechflow

ROOT = pathlib.Path(__file__).resolve().parents[1]
P1 = str(ROOT / "diagrams" / "examples" / "elast_friction.xml")
ROUNDS = 7


class Workers:
    """Processes that load P1 once and then run a given number of runs on one
    thread when told, all at the same moment: run([n1, n2]) is the wall time
    from the go to the last one's end."""

    def __init__(self, count):
        self.count = count

    def __enter__(self):
        self.procs = [subprocess.Popen([sys.executable, __file__, "--worker"], stdin=subprocess.PIPE,
                                       stdout=subprocess.PIPE, text=True) for _ in range(self.count)]
        for p in self.procs:
            assert p.stdout.readline().strip() == "ready"
        return self

    def run(self, counts):
        start = time.perf_counter()
        for p, n in zip(self.procs, counts):
            p.stdin.write(f"{n}\n")
            p.stdin.flush()
        for p, _ in zip(self.procs, counts):
            assert p.stdout.readline().strip() == "done"
        return time.perf_counter() - start

    def __exit__(self, *exc):
        for p in self.procs:
            p.stdin.close()
            p.wait()


def worker():
    d = mechflow.load(P1, variant="Free")
    d.run()
    print("ready", flush=True)
    for line in sys.stdin:
        results = d.run_many([{}] * int(line), threads=1)
        assert all(x.ok for x in results)
        del results
        print("done", flush=True)


def main():
    build = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ROOT / "build").resolve()
    runs = int(sys.argv[2]) if len(sys.argv) > 2 else 1000
    d = mechflow.load(P1, variant="Free")
    d.run()  # warm caches

    # 1. per run: the call against the simulation inside it
    calls, inside = [], []
    for _ in range(200):
        start = time.perf_counter()
        r = d.run()
        calls.append(time.perf_counter() - start)
        inside.append(r.stats["wall_seconds"])
    call, sim = statistics.median(calls), statistics.median(inside)
    print(f"P1 ({P1.split('/')[-1]} --variant Free, {len(r.time)} rows): median of 200")
    print(f"  d.run() {call * 1e3:.3f} ms, the simulation inside it {sim * 1e3:.3f} ms: ratio {call / sim:.3f}")

    # 2. run_many on 1 and 2 threads, against what two processes give on
    # this machine at the same moments (the machine's own ceiling: other
    # guests' load slows two busy cores now and then, threads or not)
    batch = [{}] * runs
    times = {"1 thread": [], "2 threads": [], "1 process": [], "2 processes": []}
    with Workers(2) as workers:
        for k in range(ROUNDS):
            for threads in ((1, 2) if k % 2 == 0 else (2, 1)):  # alternate which goes first
                start = time.perf_counter()
                results = d.run_many(batch, threads=threads)
                times[f"{threads} thread{'s' if threads > 1 else ''}"].append(time.perf_counter() - start)
                assert all(x.ok for x in results)
                del results
            times["1 process"].append(workers.run([runs]))
            times["2 processes"].append(workers.run([runs // 2, runs - runs // 2]))
    best = {key: min(value) for key, value in times.items()}
    threads = best["1 thread"] / best["2 threads"]
    processes = best["1 process"] / best["2 processes"]
    paired = [a / b for a, b in zip(times["1 thread"], times["2 threads"])]
    machine = [a / b for a, b in zip(times["1 process"], times["2 processes"])]
    print(f"  run_many of {runs}, best of {ROUNDS} alternating rounds: 1 thread {best['1 thread']:.3f} s, "
          f"2 threads {best['2 threads']:.3f} s: speed-up {threads:.2f} "
          f"(round by round: median {statistics.median(paired):.2f}, {min(paired):.2f} to {max(paired):.2f})")
    print(f"  the same runs in 1 and 2 processes of 1 thread: speed-up {processes:.2f} "
          f"(round by round: median {statistics.median(machine):.2f}, {min(machine):.2f} to {max(machine):.2f}; "
          f"{os.cpu_count()} cores)")
    print(f"  2 threads reach {threads / processes:.2f} of what 2 processes reach")

    # 3. a Python loop against processes
    start = time.perf_counter()
    for _ in range(runs):
        d.run()
    loop = time.perf_counter() - start
    exe = str(build / "mechflow")
    with tempfile.TemporaryDirectory() as out:
        start = time.perf_counter()
        for _ in range(runs):
            subprocess.run([exe, "run", P1, "--variant", "Free", "--no-plot", "--overwrite", "--out", out],
                           check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        processes = time.perf_counter() - start
    print(f"  {runs} runs: a Python loop {loop:.2f} s, {runs} `mechflow run` processes {processes:.2f} s: "
          f"ratio {processes / loop:.1f}")


if __name__ == "__main__":
    worker() if sys.argv[1:] == ["--worker"] else main()
