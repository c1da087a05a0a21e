"""Runs from Python against `mechflow run`'s results of the same diagram."""

import os
import unittest

import numpy as np

import mechflow
import support


class RunTest(unittest.TestCase):
    def assert_same_as_cli(self, result, diagram, *cli_args):
        header, rows = support.cli_results(diagram, *cli_args)
        self.assertEqual(result.columns, header)
        self.assertEqual(len(result), rows.shape[0])
        for c, name in enumerate(header):
            # bit for bit: the CSV writes the shortest text that reads back as the same double
            np.testing.assert_array_equal(result[name], rows[:, c], err_msg=name)

    def test_columns_equal_the_command_lines_bit_for_bit(self):
        d = mechflow.load(support.example("damping_ratio.xml"))
        r = d.run()
        self.assertEqual(r.status, "ok")
        self.assertEqual(r.columns, ["time", "m.z", "m.force"])
        self.assertEqual(r.t_reached, 10.0)
        self.assertEqual(len(r), 2001)
        self.assert_same_as_cli(r, support.example("damping_ratio.xml"))

    def test_set_t_end_and_interval_as_the_options(self):
        d = mechflow.load(support.example("damping_ratio.xml"))
        r = d.run(t_end=2, interval=0.01, set={"beta": 0.3})
        self.assertEqual(len(r), 201)
        self.assert_same_as_cli(r, support.example("damping_ratio.xml"), "--t-end", "2", "--interval", "0.01",
                                "--set", "beta=0.3")

    def test_set_holds_for_its_run_only(self):
        d = mechflow.load(support.example("damping_ratio.xml"))
        before = d.run(t_end=1)
        other = d.run(t_end=1, set={"beta": 0.5})
        after = d.run(t_end=1)
        self.assertFalse(np.array_equal(before["m.z"], other["m.z"]))
        np.testing.assert_array_equal(before["m.z"], after["m.z"])
        self.assertEqual({i.name: i.value for i in d.identifiers}["beta"], 0.1)

    def test_load_set_and_expressions(self):
        d = mechflow.load(support.example("damping_ratio.xml"), set={"mass": 2000, "f": "2*1.5"})
        ids = {i.name: i for i in d.identifiers}
        self.assertEqual(ids["mass"].value, 2000)
        self.assertEqual(ids["mass"].unit, "kg")
        self.assertEqual(ids["f"].value, 3)
        self.assertTrue(ids["cstiff"].derived)
        self.assertAlmostEqual(ids["cstiff"].value, 4 * np.pi**2 * 9 * 2000, delta=1e-6)
        self.assert_same_as_cli(d.run(t_end=1), support.example("damping_ratio.xml"), "--t-end", "1", "--set",
                                "mass=2000", "--set", "f=2*1.5")
        # a run's number replaces the load's expression (and the reverse)
        self.assert_same_as_cli(d.run(t_end=1, set={"F": 2}), support.example("damping_ratio.xml"), "--t-end", "1",
                                "--set", "mass=2000", "--set", "f=2")
        self.assert_same_as_cli(d.run(t_end=1, set={"mass": "500*3"}), support.example("damping_ratio.xml"),
                                "--t-end", "1", "--set", "mass=1500", "--set", "f=2*1.5")

    def test_rows_at_exactly_the_given_times(self):
        d = mechflow.load(support.example("damping_ratio.xml"))
        times = [0.0137, 0.3, 0.30000001, 1.2345678, 2.0]
        r = d.run(t_end=2, times=times, set={"beta": 0.2})
        self.assertEqual(list(r.time), times)
        # against the analytic solution: a 1 Hz oscillator with damping ratio 0.2 about its rest
        # position q = 0 (the spring force holds the weight there), released at rest 0.5 m above it
        zeta, w = 0.2, 2 * np.pi
        wd = w * np.sqrt(1 - zeta**2)
        t = np.array(times)
        expected = 0.5 * np.exp(-zeta * w * t) * (np.cos(wd * t) + zeta * w / wd * np.sin(wd * t))
        np.testing.assert_allclose(r["m.z"], expected, atol=1e-7)

    def test_log_chooses_the_columns(self):
        d = mechflow.load(support.example("damping_ratio.xml"))
        self.assertIn("m.z", d.signals)
        r = d.run(t_end=0.5, log=["m.z"])
        self.assertEqual(r.columns, ["time", "m.z"])
        self.assertEqual(r.units["m.z"], d.run(t_end=0.5).units["m.z"])  # the signal's own unit, as its <log>'s
        self.assertEqual(r.units["m.z"], "m")
        np.testing.assert_array_equal(r["m.z"], d.run(t_end=0.5)["m.z"])

    def test_to_numpy_and_to_pandas(self):
        r = mechflow.load(support.example("damping_ratio.xml")).run(t_end=1)
        a = r.to_numpy()
        self.assertEqual(a.dtype.names, ("time", "m.z", "m.force"))
        self.assertEqual(a.shape, (201,))
        np.testing.assert_array_equal(a["m.force"], r["m.force"])
        frame = r.to_pandas()
        self.assertEqual(list(frame.columns), ["m.z", "m.force"])
        self.assertEqual(frame.index.name, "time")
        self.assertEqual(frame.shape, (201, 2))
        np.testing.assert_array_equal(frame["m.z"].to_numpy(), r["m.z"])
        np.testing.assert_array_equal(frame.index.to_numpy(), r.time)

    def test_a_wrong_column_names_the_nearest(self):
        r = mechflow.load(support.example("damping_ratio.xml")).run(t_end=0.1)
        with self.assertRaises(KeyError) as e:
            r["m.zz"]
        self.assertIn("m.z", str(e.exception))

    def test_figures_units_events_stats(self):
        diagram = support.example("pendulum_pd_control.xml")
        d = mechflow.load(diagram)
        r = d.run()
        self.assertTrue(r.figures)
        # the figures as `mechflow run` prints them (6 significant digits)
        printed = support.mechflow("run", diagram, "--out", support.temp_dir("figures_"), "--no-plot",
                                   "--no-animate").stdout
        for f in r.figures:
            self.assertTrue(f.found)
            self.assertIn(f"{f.label}: {f.value:.6g}", printed)
        self.assertEqual(r.units["time"], "s")
        self.assertGreater(r.stats["steps"], 0)
        self.assertGreater(r.stats["rhs_evaluations"], r.stats["steps"])
        self.assertIn("mechflow.Result ok", repr(r))

    def test_events_are_named(self):
        d = mechflow.load(support.example("bouncing_ball_blocks.xml"))
        r = d.run()
        self.assertGreater(len(r.events), 0)
        self.assertEqual(r.stats["events"], len(r.events))
        verbose = support.mechflow("run", support.example("bouncing_ball_blocks.xml"), "--out",
                                   support.temp_dir("events_"), "--no-plot", "--no-animate", "--verbose").stdout
        first = r.events[0]
        self.assertIn(f"event: t = {first.time:.9g} s: {first.name}", verbose)

    def test_check_as_data(self):
        d = mechflow.load(support.example("damping_ratio.xml"))
        c = d.check()
        printed = support.mechflow("check", support.example("damping_ratio.xml")).stdout
        self.assertIn(f"{c['blocks']} blocks, {c['connections']} connections, {c['num_states']} continuous states",
                      printed)
        self.assertEqual(c["states"], ["m.q:jBox", "m.v:jBox"])
        self.assertEqual(c["solver"]["t_end"], 10)
        self.assertEqual(c["algebraic_loops"], [])
        for step, node in enumerate(c["schedule"], start=1):
            if node["kind"] == "output":
                self.assertIn(f"{step}. {node['port']}  ({node['type']})", printed)


if __name__ == "__main__":
    unittest.main()
