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


def test_the_pvd_series_reads_into_numpy_and_falls_freely_before_landing(tmp_path, monkeypatch):
    # meshio is installed by scripts/test.sh, so this runs in CI (not skipped there).
    pytest.importorskip("meshio")
    import rdem
    import read_pvd

    monkeypatch.chdir(tmp_path)
    sim = rdem.Simulation()
    sim.commands(read_pvd.POUR)
    series = read_pvd.read_series("post/bed.pvd")
    # A snapshot at step 1 and every 2000 steps up to 16000, each with all 500 beads.
    assert [round(t, 5) for t, _, _ in series] == [1e-5] + [0.02 * k for k in range(1, 9)]
    assert all(len(x) == 500 for _, x, _ in series)
    # Until step 2000 nothing touches anything: the centre of mass falls freely from
    # rest at step 0 (inserted at rest, one step of gravity before the first snapshot).
    g = 9.81
    (t0, x0, d0), (t1, x1, d1) = series[0], series[1]
    drop = x0[:, 2].mean() - x1[:, 2].mean()
    assert drop == pytest.approx(0.5 * g * (t1**2 - t0**2), rel=1e-3)
    # rdem writes vx vy vz as one vector field "v" (as LIGGGHTS' custom/vtk does).
    assert sorted(d1) == ["id", "mass", "radius", "type", "v"]
    assert d1["v"][:, 2].mean() == pytest.approx(-g * t1, rel=1e-3)
    # At the end the bed has settled on the floor: kinetic energy far below the
    # beads' potential energy at the start (about 0.5 * 500 * 1.3e-6 kg * g * 0.033 m).
    t, x, d = series[-1]
    assert read_pvd.kinetic_energy(d) < 1e-6
    assert x[:, 2].max() < 0.01
