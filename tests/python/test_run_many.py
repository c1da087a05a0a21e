"""run_many: C++ threads, results in input order, equal to single runs."""

import time
import unittest

import numpy as np

import mechflow
import support


class RunManyTest(unittest.TestCase):
    def test_equals_single_runs_in_input_order(self):
        d = mechflow.load(support.example("damping_ratio.xml"))
        runs = [{"set": {"beta": b}, "t_end": 3} for b in (0.02, 0.05, 0.1, 0.2, 0.4)]
        many = d.run_many(runs, threads=3)
        self.assertEqual(len(many), len(runs))
        for keywords, r in zip(runs, many):
            single = d.run(**keywords)
            self.assertEqual(r.status, "ok")
            self.assertIsNone(r.error)
            self.assertEqual(r.columns, single.columns)
            for name in r.columns:
                np.testing.assert_array_equal(r[name], single[name], err_msg=name)

    def test_a_run_keeps_nothing_of_the_run_before(self):
        # one thread runs them all in turn: the set= of one must not reach the next
        d = mechflow.load(support.example("damping_ratio.xml"))
        plain = d.run(t_end=1)
        many = d.run_many([{"set": {"beta": 0.3}, "t_end": 1}, {"t_end": 1}, {"set": {"beta": "0.15 * 2"}, "t_end": 1}],
                          threads=1)
        np.testing.assert_array_equal(many[1]["m.z"], plain["m.z"])
        np.testing.assert_array_equal(many[2]["m.z"], many[0]["m.z"])
        self.assertFalse(np.array_equal(many[0]["m.z"], plain["m.z"]))

    def test_a_failing_run_does_not_stop_the_others(self):
        d = mechflow.load(support.example("damping_ratio.xml"))
        many = d.run_many([{"t_end": 1}, {"set": {"no_such": 1}}, {"log": ["m.nothing"]}, {"t_end": 0.5}], threads=2)
        self.assertEqual([r.status for r in many], ["ok", "failed", "failed", "ok"])
        self.assertIsInstance(many[1].error, mechflow.DiagramError)
        self.assertIn("no identifier named 'no_such'", str(many[1].error))
        self.assertIsInstance(many[2].error, mechflow.DiagramError)
        self.assertEqual(len(many[3]), 101)

    def test_a_run_that_fails_part_way_keeps_its_rows(self):
        from test_errors import FAILING
        d = mechflow.load(support.write(support.temp_dir("many_fails_"), "fails.xml", FAILING))
        many = d.run_many([{}, {"t_end": 0.3}])
        self.assertEqual([r.status for r in many], ["failed", "ok"])
        error = many[0].error
        self.assertIsInstance(error, mechflow.SimulationError)
        self.assertIn("too late", str(error))
        self.assertEqual(error.time, many[0].t_reached)
        self.assertIs(error.result, many[0])
        single = None
        try:
            d.run()
        except mechflow.SimulationError as e:
            single = e.result
        np.testing.assert_array_equal(many[0]["box.x"], single["box.x"])

    def test_time_on_one_and_two_threads(self):
        d = mechflow.load(support.example("damping_ratio.xml"))
        runs = [{"set": {"beta": 0.05 + 0.01 * k}} for k in range(8)]
        start = time.perf_counter()
        d.run_many(runs, threads=1)
        one = time.perf_counter() - start
        start = time.perf_counter()
        d.run_many(runs, threads=2)
        two = time.perf_counter() - start
        # a measurement, not a check: the machine's cores may be busy with other work
        print(f"run_many of 8 damping_ratio runs: {one:.3f} s on 1 thread, {two:.3f} s on 2")

    def test_unknown_keyword_is_refused(self):
        d = mechflow.load(support.example("damping_ratio.xml"))
        with self.assertRaises(TypeError):
            d.run_many([{"tend": 1}])


if __name__ == "__main__":
    unittest.main()
