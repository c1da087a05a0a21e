"""Errors: DiagramError with file and line, SimulationError with time and rows."""

import os
import unittest

import mechflow
import support

FAILING = """<diagram name="fails">
  <blocks>
    <block type="lua" name="box" outputs="x" states="x" initial="0">
      function derivatives(t, x)
        if t > 0.5 then error("too late") end
        return 1
      end
    </block>
  </blocks>
  <solver t_end="1"/>
  <output interval="0.1"><log signal="box.x"/></output>
</diagram>
"""


class ErrorsTest(unittest.TestCase):
    def test_bad_input_names_file_and_line(self):
        folder = support.temp_dir("bad_")
        path = support.write(folder, "bad.xml", '<diagram name="bad">\n  <blocks>\n'
                             '    <block type="no_such_type" name="b"/>\n  </blocks>\n</diagram>\n')
        with self.assertRaises(mechflow.DiagramError) as e:
            mechflow.load(path)
        self.assertEqual(e.exception.file, path)
        self.assertEqual(e.exception.line, 3)
        self.assertIsInstance(e.exception, mechflow.Error)
        # the command line's message, word for word
        self.assertIn(str(e.exception), support.mechflow("check", path, check=False).stderr)

    def test_a_missing_file(self):
        with self.assertRaises(mechflow.DiagramError) as e:
            mechflow.load(os.path.join(support.temp_dir("missing_"), "none.xml"))
        self.assertIn("none.xml", str(e.exception))

    def test_unknown_set_name_without_a_line(self):
        d = mechflow.load(support.example("damping_ratio.xml"))
        with self.assertRaises(mechflow.DiagramError) as e:
            d.run(set={"betta": 0.2})
        self.assertIn("did you mean", str(e.exception).lower())
        self.assertIsNone(e.exception.line)

    def test_a_failed_run_carries_its_time_and_rows(self):
        path = support.write(support.temp_dir("fails_"), "fails.xml", FAILING)
        d = mechflow.load(path)
        with self.assertRaises(mechflow.SimulationError) as e:
            d.run()
        error = e.exception
        self.assertIsInstance(error, mechflow.Error)
        self.assertIn("too late", str(error))
        self.assertAlmostEqual(error.time, 0.5, delta=1e-3)  # the last step accepted
        r = error.result
        self.assertEqual(r.status, "failed")
        self.assertEqual(r.t_reached, error.time)
        # the command line's rows up to the failure
        out = support.temp_dir("fails_cli_")
        done = support.mechflow("run", path, "--out", out, "--no-plot", check=False)
        self.assertEqual(done.returncode, 1)
        header, rows = support.read_csv(os.path.join(out, "fails.csv"))
        self.assertEqual(r.columns, header)
        self.assertEqual(list(r["box.x"]), list(rows[:, 1]))
        self.assertIn(f"simulation failed at t = {error.time:g} s", done.stderr)
        self.assertTrue(str(error).startswith(f"simulation failed at t = {error.time:g} s: "), str(error))

    def test_keywords_of_the_wrong_kind_are_named(self):
        d = mechflow.load(support.example("damping_ratio.xml"))
        with self.assertRaisesRegex(TypeError, "t_end must be a number, not str '3'"):
            d.run(t_end="3")
        with self.assertRaisesRegex(ValueError, "times is empty"):
            d.run(times=[])
        with self.assertRaisesRegex(TypeError, "set must be a dict"):
            d.run(set=[("beta", 0.1)])
        with self.assertRaisesRegex(TypeError, "run_many: run 1: rtol must be a number"):
            d.run_many([{}, {"rtol": "1e-6"}])
        with self.assertRaisesRegex(TypeError, "run_many: run 0 is a int, not a dict"):
            d.run_many([1, {}])

    def test_times_it_cannot_keep_are_refused(self):
        d = mechflow.load(support.example("damping_ratio.xml"))
        with self.assertRaises(mechflow.DiagramError) as e:
            d.run(times=[0.2, 0.1])
        self.assertIn("the output time 0.1 s (number 2 in the list) is not after the one before (0.2 s)", str(e.exception))
        with self.assertRaises(mechflow.DiagramError) as e:
            d.run(times=[0.5], interval=0.01)
        self.assertIn("output at given times and an output interval exclude each other", str(e.exception))
        with self.assertRaises(mechflow.DiagramError) as e:
            d.run(times=[0.5, 11])
        self.assertIn("is after t_end = 10 s", str(e.exception))

    def test_the_sandbox_is_the_command_lines(self):
        folder = support.temp_dir("sandbox_")
        path = support.write(folder, "io.xml", FAILING.replace('error("too late")', 'io.open("x")'))
        with self.assertRaises(mechflow.SimulationError) as e:
            mechflow.load(path).run()
        self.assertIn("attempt to index a nil value (global 'io')", str(e.exception))


if __name__ == "__main__":
    unittest.main()
