"""Ctrl-C during a run: KeyboardInterrupt within about a second, Python's
handler back afterwards."""

import os
import signal
import subprocess
import sys
import textwrap
import time
import unittest

import support

CHILD = textwrap.dedent("""
    import signal, sys, time
    import mechflow
    d = mechflow.load(sys.argv[1])
    handler = signal.getsignal(signal.SIGINT)
    print("ready", flush=True)
    try:
        if sys.argv[2] == "one":
            d.run(t_end=1e7)
        else:
            d.run_many([{"t_end": 1e7}] * 6, threads=2)
    except mechflow.RunInterrupted as e:
        if e.result is not None:
            print("interrupted", e.result.status, len(e.result), flush=True)
        else:
            print("interrupted", sorted({r.status for r in e.results}), flush=True)
        assert signal.getsignal(signal.SIGINT) is handler
        print("handler restored", flush=True)
        sys.exit(3)
    print("not interrupted", flush=True)
""")


def endless_diagram():
    with open(support.example("stick_slip_blocks.xml")) as f:
        xml = f.read().replace('interval="0.001"', 'interval="0.5"')
    return support.write(support.temp_dir("endless_"), "stick_slip_blocks.xml", xml)


class InterruptTest(unittest.TestCase):
    def interrupt(self, mode):
        child = subprocess.Popen([sys.executable, "-c", CHILD, endless_diagram(), mode], stdout=subprocess.PIPE,
                                 stderr=subprocess.PIPE, text=True, env=os.environ)
        self.assertEqual(child.stdout.readline().strip(), "ready")
        time.sleep(0.5)
        sent = time.monotonic()
        child.send_signal(signal.SIGINT)
        try:
            out, err = child.communicate(timeout=10)
        except subprocess.TimeoutExpired:
            child.kill()
            self.fail("the run went on after SIGINT")
        waited = time.monotonic() - sent
        print(f"{mode}: ended {waited:.3f} s after SIGINT")
        self.assertEqual(child.returncode, 3, err)
        self.assertIn("handler restored", out)
        self.assertLess(waited, 1.5)
        return out

    def test_pythons_handler_is_back_after_a_run(self):
        import mechflow
        d = mechflow.load(support.example("damping_ratio.xml"))
        d.run(t_end=0.1)
        d.run_many([{"t_end": 0.1}] * 2, threads=2)
        with self.assertRaises(KeyboardInterrupt) as e:
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(1)  # Python runs its handler between bytecodes: at once
        self.assertNotIsInstance(e.exception, mechflow.RunInterrupted)

    def test_a_run_ends_with_keyboard_interrupt(self):
        out = self.interrupt("one")
        self.assertIn("interrupted interrupted", out)

    def test_run_many_ends_every_run(self):
        out = self.interrupt("many")
        self.assertIn("interrupted ['interrupted']", out)


if __name__ == "__main__":
    unittest.main()
