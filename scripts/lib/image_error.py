"""An image's error against a reference, for the charts that plot error against time
(bench-charts.py, bench-peer-error.py): numpy and Mitsuba 3 from the venv of scripts/lib/venv.sh; the
caller sets Mitsuba's variant (any reads an EXR)."""
import mitsuba as mi
import numpy as np


def read_exr(path):
    """The RGB channels of an EXR, in double."""
    return np.array(mi.Bitmap(path), dtype=np.float64)[..., :3]


def rel_rmse(image, reference):
    """The root of the mean squared difference over the reference's mean."""
    return float(np.sqrt(np.mean((image - reference) ** 2)) / max(np.mean(reference), 1e-12))
