#!/usr/bin/env python3
"""What a run through the Python module costs, as ratios measured in one go.

P1 (the seed ElastFriction, variant Free: a box sliding to rest on a
frictional element, 2 s, its 1 ms output grid):

1. a run through the module with its rows in memory against the simulator's
   own time for the same run (RunResult's wall time around the simulation
   alone): the module's overhead per run (building the run from the kept
   description, handing rows to numpy);
2. run_many of RUNS runs on 2 threads against 1 thread;
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

    # 2. run_many on 1 and 2 threads
    batch = [{}] * runs
    times = {}
    for threads in (1, 2):
        best = []
        for _ in range(3):
            start = time.perf_counter()
            results = d.run_many(batch, threads=threads)
            best.append(time.perf_counter() - start)
            assert all(x.ok for x in results)
        times[threads] = statistics.median(best)
    print(f"  run_many of {runs}: 1 thread {times[1]:.3f} s, 2 threads {times[2]:.3f} s: "
          f"speed-up {times[1] / times[2]:.2f} ({os.cpu_count()} cores)")

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
    main()
