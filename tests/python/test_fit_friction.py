"""examples/python/fit_friction.py, run as a user runs it: scipy's
least_squares recovers the friction coefficients a different model's noisy
measurement was made with."""

import os
import re
import subprocess
import sys
import unittest

import support


class FitFrictionExampleTest(unittest.TestCase):
    def test_recovers_mu_and_mu_s_of_the_measurement(self):
        script = os.path.join(support.SOURCE_DIR, "examples", "python", "fit_friction.py")
        done = subprocess.run([sys.executable, script], capture_output=True, text=True, timeout=300)
        self.assertEqual(done.returncode, 0, done.stderr)
        found = {}
        for name in ("mu", "mu_s"):
            m = re.search(rf"^{name} += ([0-9.]+) \+- ([0-9.]+)", done.stdout, re.M)
            self.assertIsNotNone(m, done.stdout)
            found[name] = (float(m.group(1)), float(m.group(2)))
        # the two models differ (four contact points against one equation):
        # the coefficients come back within 1 % of the truth, not to the noise
        self.assertAlmostEqual(found["mu"][0], 0.3, delta=0.003)
        self.assertAlmostEqual(found["mu_s"][0], 0.4, delta=0.004)
        for value, error in found.values():
            self.assertGreater(error, 0.0)
            self.assertLess(error, 0.01)
        m = re.search(r"cost ([0-9.e+-]+) -> ([0-9.e+-]+) in (\d+) runs", done.stdout)
        self.assertIsNotNone(m, done.stdout)
        self.assertLess(float(m.group(2)), 0.01 * float(m.group(1)))


if __name__ == "__main__":
    unittest.main()
