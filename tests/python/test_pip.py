"""`pip install .` into a fresh virtual environment (reusing the build tree
the tests run from, MECHFLOW_BUILD_DIR), then a diagram run by the
installed module."""

import os
import subprocess
import sys
import unittest

import support


class PipTest(unittest.TestCase):
    def test_install_into_a_venv_and_run(self):
        build = os.environ.get("MECHFLOW_BUILD_DIR")
        if not build:
            self.skipTest("MECHFLOW_BUILD_DIR not set (CTest sets it)")
        venv = os.path.join(support.temp_dir("venv_"), "v")
        subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", venv], check=True)
        python = os.path.join(venv, "bin", "python")
        env = dict(os.environ)
        env.pop("PYTHONPATH", None)  # the installed module, not the build tree's
        done = subprocess.run([os.path.join(venv, "bin", "pip"), "install", "--no-index", "--no-build-isolation",
                               "--quiet", support.SOURCE_DIR], env=env, capture_output=True, text=True)
        self.assertEqual(done.returncode, 0, done.stdout + done.stderr)
        script = ("import mechflow, sys\n"
                  "r = mechflow.load(sys.argv[1]).run(t_end=1)\n"
                  "print(mechflow.__file__)\n"
                  "print(r.status, len(r), r['m.z'][-1])\n")
        done = subprocess.run([python, "-c", script, support.example("damping_ratio.xml")], env=env,
                              capture_output=True, text=True, cwd=venv)
        self.assertEqual(done.returncode, 0, done.stderr)
        where, figures = done.stdout.splitlines()
        self.assertTrue(where.startswith(venv), where)
        self.assertTrue(figures.startswith("ok 201 "), figures)


if __name__ == "__main__":
    unittest.main()
