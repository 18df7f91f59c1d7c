"""The Python examples: the calibration sweep's trend, on a cut-down sweep."""

import os
import sys

import pytest

# The examples are scripts, not a package: imported by name (multiprocessing's workers
# find the functions by their module).
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples", "python"))


def test_the_bed_stands_taller_with_more_friction():
    import calibrate_friction as calib

    # Three of the example's eight frictions, in two processes as the example runs them.
    # Measured (2000 beads): 4.28, 4.49 and 4.67 mm for 0, 0.2 and 1.0.
    results = calib.sweep([0.0, 0.2, 1.0], processes=2)
    heights = [h for h, _ in results]
    assert heights[0] < heights[1] < heights[2], heights
    assert heights[0] == pytest.approx(4.28e-3, rel=0.03)
    # Settled: the kinetic energy left is tiny (the beads' potential energy is ~1e-5 J).
    assert all(ke < 1e-6 for _, ke in results), results
