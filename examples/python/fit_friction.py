#!/usr/bin/env python3
"""Fit the friction coefficients of a stick-slip model to a measured position.

The "measurement" is made by one model and fitted with another, as a test rig
and its model differ:

* measured: the example oscillations.xml (a box on four penalty contact
  points, pulled through a spring by a leader), run with the true
  coefficients mu = 0.3, mu_s = 0.4, its position sampled at 200 Hz with
  seeded noise (0.2 mm standard deviation);
* fitted: pulled_block.xml beside this script, the same physics as one
  equation of signal blocks (normal force m g, no contact points).

scipy's least_squares varies mu and mu_s - mu (so that mu_s >= mu always)
within bounds; each residual evaluation is one run of the loaded diagram with
output at exactly the measured instants (no file, no parse, no interpolation).

    python3 examples/python/fit_friction.py

Prints the fitted coefficients with standard errors (from the Jacobian at the
solution and the residuals' variance), the cost before and after, and the
number of runs.
"""

import argparse
import pathlib
import sys

import numpy as np
from scipy.optimize import least_squares

import mechflow

HERE = pathlib.Path(__file__).resolve().parent
OSCILLATIONS = HERE.parent.parent / "diagrams" / "examples" / "oscillations.xml"
TRUTH = {"mu": 0.3, "mu_s": 0.4}


def measure(times, sigma=2e-4, seed=7):
    """Position of the contact model at `times`, with seeded Gaussian noise."""
    rig = mechflow.load(str(OSCILLATIONS))
    run = rig.run(set=TRUTH, t_end=times[-1], times=times, log=["m.x"])
    noise = np.random.default_rng(seed).normal(0.0, sigma, times.size)
    return run["m.x"] + noise


def fit(times, measured, start=(0.25, 0.05)):
    """Least-squares fit of (mu, mu_s - mu) of pulled_block.xml.

    Returns a dict: mu, mu_s, their standard errors, the cost before and
    after and the number of runs."""
    model = mechflow.load(str(HERE / "pulled_block.xml"))
    runs = 0

    def residuals(p):
        nonlocal runs
        runs += 1
        run = model.run(set={"mu": p[0], "mu_s": p[0] + p[1]}, t_end=times[-1], times=times, log=["x.y"])
        return run["x.y"] - measured

    cost_before = 0.5 * float(np.sum(residuals(np.asarray(start)) ** 2))
    solution = least_squares(residuals, start, bounds=([0.01, 0.0], [1.0, 1.0]), diff_step=1e-4, x_scale=0.1)
    # covariance of (mu, delta): s^2 (J^T J)^-1, s^2 the residuals' variance
    jac = solution.jac
    dof = times.size - len(solution.x)
    variance = 2.0 * solution.cost / dof
    covariance = variance * np.linalg.inv(jac.T @ jac)
    # mu_s = mu + delta: its variance adds the covariance term
    to_mu_s = np.array([1.0, 1.0])
    mu, delta = solution.x
    return {
        "mu": mu,
        "mu_s": mu + delta,
        "se_mu": float(np.sqrt(covariance[0, 0])),
        "se_mu_s": float(np.sqrt(to_mu_s @ covariance @ to_mu_s)),
        "cost_before": cost_before,
        "cost_after": float(solution.cost),
        "runs": runs,
    }


def main():
    argparse.ArgumentParser(description=__doc__.splitlines()[0]).parse_args()
    times = np.round(np.arange(1, 601) * 0.005, 12)  # 200 Hz for 3 s
    measured = measure(times)
    result = fit(times, measured)
    print(f"mu   = {result['mu']:.5f} +- {result['se_mu']:.5f}   (measured with {TRUTH['mu']})")
    print(f"mu_s = {result['mu_s']:.5f} +- {result['se_mu_s']:.5f}   (measured with {TRUTH['mu_s']})")
    print(f"cost {result['cost_before']:.4g} -> {result['cost_after']:.4g} in {result['runs']} runs")
    return 0


if __name__ == "__main__":
    sys.exit(main())
