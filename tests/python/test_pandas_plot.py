"""A run's table through pandas into a matplotlib plot: the PNG is read back
and the curve is found where the closed form of the damped oscillator puts it."""

import math
import os
import unittest

import numpy as np

import mechflow
import support


def closed_form(t, x0=0.5, f=1.0, beta=0.1):
    w = 2.0 * math.pi * f
    wd = w * math.sqrt(1.0 - beta * beta)
    return x0 * np.exp(-beta * w * t) * (np.cos(wd * t) + beta * w / wd * np.sin(wd * t))


class PandasPlotTest(unittest.TestCase):
    def test_the_plot_shows_the_runs_data(self):
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.image
        import matplotlib.pyplot as plt

        frame = mechflow.load(support.example("damped_oscillator_blocks.xml")).run(t_end=4.0).to_pandas()
        self.assertEqual(list(frame.columns), ["x", "v"])
        self.assertEqual(frame.index.name, "time")
        self.assertEqual(set(frame.attrs["units"]), {"time", "x", "v"})
        self.assertEqual(len(frame), 401)
        np.testing.assert_allclose(frame["x"], closed_form(frame.index.to_numpy()), atol=1e-6)

        fig, ax = plt.subplots(figsize=(6, 4), dpi=100)
        ax.plot(frame.index, frame["x"], color="#ff0000", linewidth=1.5)
        ax.set_xlim(0.0, 4.0)
        ax.set_ylim(-0.5, 0.55)
        ax.set_xlabel("time [s]")
        ax.set_ylabel("x [m]")
        fig.canvas.draw()
        to_pixels = ax.transData  # data -> display pixels, origin bottom left
        png = os.path.join(support.temp_dir("pandas_plot_"), "x.png")
        fig.savefig(png)
        plt.close(fig)
        image = matplotlib.image.imread(png)
        height = image.shape[0]
        red = (image[:, :, 0] > 0.8) & (image[:, :, 1] < 0.3) & (image[:, :, 2] < 0.3)
        self.assertGreater(red.sum(), 500)
        # every 10th sample of the closed form lies on a red pixel (within 2)
        for t in np.arange(0.05, 4.0, 0.1):
            px, py = to_pixels.transform((t, closed_form(t)))
            col, row = int(round(px)), int(round(height - py))
            window = red[row - 2 : row + 3, col - 2 : col + 3]
            self.assertTrue(window.any(), f"no curve at t = {t:.2f} s (pixel {col}, {row})")
        # and nothing red where the curve is not: at the mirror of the first peak
        px, py = to_pixels.transform((0.0, -0.45))
        self.assertFalse(red[int(round(height - py)) - 3 : int(round(height - py)) + 4, int(px) : int(px) + 20].any())


if __name__ == "__main__":
    unittest.main()
