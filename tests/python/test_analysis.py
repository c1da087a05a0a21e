"""Modes, spectra and force analysis against the command line's files."""

import math
import os
import unittest

import numpy as np

import mechflow
import support


class ModesTest(unittest.TestCase):
    def check_against_cli(self, diagram, *args, equilibrium=False):
        out = support.temp_dir("modes_")
        support.mechflow("modes", diagram, "--out", out, *args, *(["--equilibrium"] if equilibrium else []))
        name = [f for f in os.listdir(out) if f.endswith(".modes.csv")][0]
        header, rows = support.read_csv(os.path.join(out, name))
        return header, rows

    def test_modes_equal_the_command_lines_csv(self):
        diagram = support.example("three_masses_blocks.xml")
        m = mechflow.load(diagram).modes()
        header, rows = self.check_against_cli(diagram)
        self.assertEqual(len(m), rows.shape[0])
        self.assertEqual(m.states, header[6:])
        # the CSV holds the shortest text of each double: exact
        np.testing.assert_array_equal(m.frequency, rows[:, 1])
        np.testing.assert_array_equal(m.natural_frequency, rows[:, 2])
        np.testing.assert_array_equal(m.damping_ratio, rows[:, 3])
        np.testing.assert_array_equal(m.eigenvalues.real, rows[:, 4])
        np.testing.assert_array_equal(m.eigenvalues.imag, rows[:, 5])
        np.testing.assert_array_equal(m.shapes.T, rows[:, 6:])
        self.assertIsNone(m.equilibrium)

    def test_damping_ratio_at_the_equilibrium(self):
        diagram = support.example("damping_ratio.xml")
        m = mechflow.load(diagram).modes(equilibrium=True, set={"beta": 0.2})
        header, rows = self.check_against_cli(diagram, "--set", "beta=0.2", equilibrium=True)
        np.testing.assert_array_equal(m.damping_ratio, rows[:, 3])
        # the model's own: f = 1 Hz undamped, zeta = beta
        self.assertAlmostEqual(m.natural_frequency[0], 1.0, places=6)
        self.assertAlmostEqual(m.damping_ratio[0], 0.2, places=6)
        self.assertEqual(m.kinds[0], "oscillating")
        self.assertIsNotNone(m.equilibrium)

    def test_no_states_is_bad_input(self):
        folder = support.temp_dir("nostates_")
        path = support.write(folder, "d.xml", "<diagram name='d'>\n<blocks><block type='expression' name='f' "
                             "inputs='' expr='1'/></blocks>\n<solver t_end='1'/>\n</diagram>\n")
        with self.assertRaises(mechflow.DiagramError) as e:
            mechflow.load(path).modes()
        self.assertIn("no continuous states", str(e.exception))


class PsdTest(unittest.TestCase):
    def test_a_sine_peaks_at_its_frequency(self):
        dt = 1e-3
        t = np.arange(20000) * dt
        s = mechflow.psd(2.0 * np.sin(2 * math.pi * 37.0 * t) + 0.5 * np.sin(2 * math.pi * 120.0 * t), dt)
        self.assertEqual(s.segment, 4096)
        self.assertAlmostEqual(s.resolution, 1000 / 4096)
        self.assertAlmostEqual(s.peak_frequency[0], 37.0, delta=0.05)
        self.assertAlmostEqual(s.peak_frequency[1], 120.0, delta=0.05)
        # Parseval: the integral of the density is the variance (2^2/2 + 0.5^2/2), to the window's leakage
        self.assertAlmostEqual(np.sum(s.density) * s.resolution, 2.125, delta=0.02)

    def test_against_the_psd_command(self):
        r = mechflow.load(support.example("damping_ratio.xml")).run(t_end=40)
        out = support.temp_dir("psd_")
        results = os.path.join(out, "d.csv")
        with open(results, "w") as f:
            f.write("time,m.z\n")
            for t, z in zip(r.time, r["m.z"]):
                f.write(f"{t!r},{z!r}\n")
        support.mechflow("psd", results, "--signal", "m.z", "--out", out)
        header, rows = support.read_csv(os.path.join(out, "d.psd.csv"))
        s = mechflow.psd(r["m.z"], 0.005)
        np.testing.assert_allclose(s.frequency, rows[:, 0], rtol=1e-15)
        np.testing.assert_allclose(s.density, rows[:, 1], rtol=1e-12)
        self.assertAlmostEqual(s.peak_frequency[0], math.sqrt(1 - 0.1**2), delta=s.resolution)

    def test_bad_options(self):
        with self.assertRaises(mechflow.DiagramError):
            mechflow.psd(np.zeros(8), 0.1)
        with self.assertRaises(mechflow.DiagramError):
            mechflow.psd(np.zeros(100), 0.1, window="triangle")


class ForceAnalysisTest(unittest.TestCase):
    def test_stiffness_as_the_command(self):
        diagram = support.example("elast_friction2.xml")
        fa = mechflow.load(diagram).force_analysis(element="friction", amplitude=[0.001, 0.003], frequency=1,
                                                   vary={("ffr", "ffr0"): [0, 0.2]}, samples=500)
        self.assertEqual(len(fa), 4)
        out = support.temp_dir("fa_")
        support.mechflow("force-analysis", diagram, "--element", "friction", "--amplitude", "0.001,0.003",
                         "--frequency", "1", "--vary", "ffr,ffr0=0,0.2", "--samples", "500", "--out", out)
        with open(os.path.join(out, "elast_friction2.force_analysis.csv")) as f:
            lines = [line.rstrip("\n").split(",") for line in f]
        self.assertEqual(lines[0][:5], ["ffr=ffr0", "amplitude", "frequency [Hz]", "x0", "K"])
        for k in range(4):
            self.assertEqual(float(lines[1 + k][0]), fa.varied[k, 0])
            self.assertEqual(float(lines[1 + k][1]), fa.amplitude[k])
            self.assertAlmostEqual(float(lines[1 + k][4]) / fa.stiffness[k], 1.0, places=8)
            self.assertEqual(lines[1 + k][8], "yes" if fa.periodic[k] else "no")
        self.assertEqual(len(fa.loops[0]["x"]), 501)
        np.testing.assert_array_equal(fa.varied[:, 0], [0, 0, 0.2, 0.2])


if __name__ == "__main__":
    unittest.main()
