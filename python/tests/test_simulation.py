"""The rdem Python module against the rdem command and its own promises.

Run by the README's test command (scripts/test.sh) after it builds and installs the
wheel in a virtual environment: ``python -m pytest python/tests``.
"""

import os
import shutil
import signal
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import rdem

# 343 spheres on a simple cubic lattice falling onto a floor (Hertz with tangential
# history): collisions from step ~300 on, so histories and contacts matter.
BED = """\
atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
region box block 0 0.04 0 0.04 0 0.08 units box
create_box 1 box
neighbor 0.002 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 5e6
fix m2 all property/global poissonsRatio peratomtype 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.6
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 1e-5
lattice sc 0.005
region pack block 0.004 0.036 0.004 0.036 0.004 0.036 units box
create_atoms 1 region pack
set type 1 diameter 0.004 density 2500
fix gravi all gravity 9.81 vector 0 0 -1
fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0
fix integr all nve/sphere
thermo_style custom step atoms ke
thermo_modify format float %.17g
thermo 50
"""

DUMP = (
    "dump d all custom 200 dump.*.txt id x y z vx vy vz\n"
    'dump_modify d sort id format "%d %.17g %.17g %.17g %.17g %.17g %.17g"\n'
)


def rdem_command():
    """The rdem command: the one this package installed, else the cargo build's."""
    here = os.path.join(os.path.dirname(sys.executable), "rdem")
    if os.path.exists(here):
        return here
    return shutil.which("rdem")


def thermo_rows(log_text):
    """The thermo rows (between each 'Step' header and 'Loop time')."""
    rows, inside = [], False
    for line in log_text.splitlines():
        if line.split()[:1] == ["Step"]:
            inside = True
        elif line.startswith("Loop time"):
            inside = False
        elif inside:
            rows.append(line)
    return rows


def dump_atoms(path):
    with open(path) as f:
        lines = f.read().splitlines()
    k = next(i for i, l in enumerate(lines) if l.startswith("ITEM: ATOMS"))
    return np.array([[float(w) for w in l.split()] for l in lines[k + 1 :]])


def test_the_cli_and_sim_file_give_the_same_thermo_and_dumps(tmp_path):
    script = BED + DUMP + "run 600\n"
    a, b = tmp_path / "cli", tmp_path / "py"
    a.mkdir()
    b.mkdir()
    (a / "in.bed").write_text(script)
    (b / "in.bed").write_text(script)
    subprocess.run(
        [rdem_command(), "-in", "in.bed", "-log", "log.a", "-screen", "none"],
        cwd=a,
        check=True,
        env={**os.environ, "RDEM_THREADS": "1"},
    )
    cwd = os.getcwd()
    os.chdir(b)
    try:
        # Two threads here, one in the command: results do not depend on the count.
        sim = rdem.Simulation(threads=2, log="log.b")
        sim.file("in.bed")
        del sim  # closes the log
    finally:
        os.chdir(cwd)
    rows_a = thermo_rows((a / "log.a").read_text())
    rows_b = thermo_rows((b / "log.b").read_text())
    assert len(rows_a) == 13 and rows_a == rows_b
    for step in (0, 200, 400, 600):
        name = f"dump.{step}.txt"
        assert (a / name).read_bytes() == (b / name).read_bytes(), name


def test_arrays_after_run_100_equal_the_dump_of_that_step(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    sim = rdem.Simulation(threads=1)
    sim.commands(BED)
    sim.command("run 100")
    sim.command(
        "write_dump all custom d100.txt id x y z vx vy vz modify sort id format "
        '"%d %.17g %.17g %.17g %.17g %.17g %.17g"'
    )
    d = dump_atoms("d100.txt")
    order = np.argsort(sim.tag)
    assert sim.natoms == 343 == len(d)
    assert sim.step == 100
    assert sim.time == pytest.approx(100 * 1e-5, rel=1e-12)
    np.testing.assert_array_equal(sim.tag[order], d[:, 0].astype(np.uint64))
    np.testing.assert_array_equal(sim.x[order], d[:, 1:4])
    np.testing.assert_array_equal(sim.v[order], d[:, 4:7])
    assert sim.radius == pytest.approx(np.full(343, 0.002))
    np.testing.assert_allclose(sim.mass, 2500 * 4 / 3 * np.pi * 0.002**3, rtol=1e-14)
    assert set(sim.type) == {1}
    # The thermo rows of the last run as columns.
    th = sim.thermo
    np.testing.assert_array_equal(th["step"], [0, 50, 100])
    assert th["ke"][0] == 0 and th["ke"][-1] > 0 and len(th["atoms"]) == 3


def test_copies_never_change_the_simulation_and_views_cannot_be_written():
    sim = rdem.Simulation(threads=1)
    sim.commands(BED)
    sim.command("run 10")
    x = sim.x
    x[:] = 0.0
    assert np.all(sim.x[:, 2] > 0.003)
    view = sim.view("x")
    np.testing.assert_array_equal(view, sim.x)
    with pytest.raises(ValueError):
        view[0, 0] = 1.0
    # A command may move the storage a view looks at: none runs while one is alive.
    with pytest.raises(RuntimeError, match="view"):
        sim.command("run 1")
    before = view.copy()
    del view
    sim.command("run 10")
    assert sim.step == 20
    assert not np.array_equal(before, sim.x)
    r = sim.view("radius")
    assert r.shape == (343,) and not r.flags.writeable
    del r


def test_a_bad_command_raises_with_its_line_and_the_simulation_goes_on():
    sim = rdem.Simulation(threads=1)
    sim.commands(BED)
    with pytest.raises(rdem.RdemError) as e:
        sim.commands("run 10\nvariable a equal 2*step\nfix bad all nve/spheer\nrun 10\n")
    err = e.value
    assert (err.file, err.line, err.column) == ("<commands>", 3, 13)
    assert "nve/spheer" in err.report and "nve/sphere" in err.report
    assert sim.step == 10
    sim.command("run 10")
    assert sim.step == 20
    assert sim.variable("a") == 40.0
    with pytest.raises(rdem.RdemError) as e:
        sim.command("run ten")
    assert e.value.line == 1 and e.value.column == 5


def test_values_of_variables_computes_and_fixes():
    sim = rdem.Simulation(threads=1)
    sim.commands(
        BED
        + "fix tag all property/atom tagged vector no no no 1.5 -2\n"
        + "set group all property/atom tagged 3 4\n"
        + "variable zc equal xcm(all,z)\nvariable r atom 2*radius\n"
        + "compute k all ke\nfix av all ave/time 1 10 10 c_k\nrun 20\n"
    )
    zc = sim.variable("zc")
    assert zc == pytest.approx(np.mean(sim.x[:, 2]), rel=1e-12)
    np.testing.assert_array_equal(sim.variable("r"), 2 * sim.radius)
    ke = 0.5 * np.sum(sim.mass[:, None] * sim.v**2)
    assert sim.compute("k") == pytest.approx(ke, rel=1e-12)
    assert sim.fix("av") > 0
    with pytest.raises(KeyError):
        sim.variable("nope")
    # A named per-particle property (two values each).
    np.testing.assert_array_equal(sim.array("tagged"), np.tile([3.0, 4.0], (343, 1)))
    with pytest.raises(KeyError, match="named per-particle property"):
        sim.array("nope")


def test_a_callback_every_n_steps_sees_the_state_and_can_stop_the_run():
    sim = rdem.Simulation(threads=1)
    sim.commands(BED)
    seen = []

    def watch(view):
        seen.append((view.step, view.natoms, float(view.x[:, 2].min())))
        return view.step < 300

    sim.set_callback(watch, every=100)
    sim.commands("run 1000\nvariable after equal step\n")
    # Called at 100, 200, 300; False at 300 ends the run there and the script goes on.
    assert [s[0] for s in seen] == [100, 200, 300]
    assert sim.step == 300 and sim.variable("after") == 300
    assert sim.thermo["step"][-1] == 300
    sim.set_callback(None)
    sim.command("run 10")
    assert sim.step == 310 and len(seen) == 3
    # A view kept after its call cannot be read.
    kept = []
    sim.set_callback(lambda v: kept.append(v), every=5)
    sim.command("run 5")
    with pytest.raises(RuntimeError, match="callback returned"):
        kept[0].x
    # An exception in the callback ends the run and is raised by the command.
    sim.set_callback(lambda v: 1 / 0, every=2)
    with pytest.raises(ZeroDivisionError):
        sim.command("run 10")
    # The first step of that run that is a multiple of 2 (316) raised.
    assert sim.step == 316


CTRL_C = """
import os, sys, time
import rdem
sim = rdem.Simulation(threads=1)
sim.commands(open("in.bed").read())
def slow(view):
    if view.step == 50:
        open("started", "w").close()
        time.sleep(1.0)   # SIGINT arrives during this step
sim.set_callback(slow)
try:
    sim.command("run 100000")
    print("not interrupted")
except KeyboardInterrupt:
    print("interrupted at", sim.step)
sim.set_callback(None)
sim.command("run 10")
print("continued to", sim.step)
"""


def test_ctrl_c_stops_a_run_after_the_current_step_and_the_next_run_goes_on(tmp_path):
    (tmp_path / "in.bed").write_text(BED)
    (tmp_path / "child.py").write_text(CTRL_C)
    p = subprocess.Popen(
        [sys.executable, "child.py"], cwd=tmp_path, stdout=subprocess.PIPE, text=True
    )
    for _ in range(600):
        if (tmp_path / "started").exists():
            break
        try:
            p.wait(0.1)
            break
        except subprocess.TimeoutExpired:
            pass
    p.send_signal(signal.SIGINT)
    out, _ = p.communicate(timeout=120)
    # The signal came during step 50's callback: step 51 is the first to see it.
    assert out.split("\n")[:2] == ["interrupted at 51", "continued to 61"], out
