"""Calibration sweep: the height of a poured bed against the particles' friction.

Pours the same particles into a square box for eight values of the sliding friction
coefficient, each run in its own process (rdem.Simulation, one thread each, two at a
time), lets the bed settle and measures its height as twice the height of its centre
of mass (exact for a uniform bed). More friction holds the particles in a looser
packing, so the bed stands taller; the plot (bed_height.png) is the curve a
calibration reads a measured height against.

    python examples/python/calibrate_friction.py        # about a minute on 2 cores

Needs the rdem package (pip install . from the repository root) and matplotlib.
"""

import sys
import time
from multiprocessing import Pool

import rdem

FRICTIONS = [0.0, 0.05, 0.1, 0.2, 0.3, 0.5, 0.7, 1.0]

# 1 mm glass beads poured into a 20 mm square box; {n} particles, friction {mu}.
SCRIPT = """\
atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
region box block 0 0.02 0 0.02 0 0.12 units box
create_box 1 box
neighbor 0.0004 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 5e6
fix m2 all property/global poissonsRatio peratomtype 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.3
fix m4 all property/global coefficientFriction peratomtypepair 1 {mu}
pair_style gran model hertz tangential history
pair_coeff * *
timestep 1e-5
fix gravi all gravity 9.81 vector 0 0 -1
fix walls all wall/gran model hertz tangential history primitive type 1 zplane 0
fix wx0 all wall/gran model hertz tangential history primitive type 1 xplane 0
fix wx1 all wall/gran model hertz tangential history primitive type 1 xplane 0.02
fix wy0 all wall/gran model hertz tangential history primitive type 1 yplane 0
fix wy1 all wall/gran model hertz tangential history primitive type 1 yplane 0.02
region ins block 0.001 0.019 0.001 0.019 0.01 0.119 units box
fix pts all particletemplate/sphere 15485863 atom_type 1 density constant 2500 radius constant 0.0005
fix pdd all particledistribution/discrete 32452843 1 pts 1.0
fix ins all insert/pack seed 49979687 distributiontemplate pdd insert_every once overlapcheck yes all_in yes particles_in_region {n} region ins
fix integr all nve/sphere
variable zc equal xcm(all,z)
variable ke equal ke
thermo_style custom step atoms ke v_zc
thermo 5000
"""


def bed_height(mu, n=2000, steps=30000):
    """Pours `n` particles with friction `mu`, runs `steps` steps; returns (height, KE)."""
    sim = rdem.Simulation(threads=1)
    sim.commands(SCRIPT.format(mu=mu, n=n))
    sim.command(f"run {steps}")
    return 2.0 * sim.variable("zc"), sim.variable("ke")


def sweep(frictions, processes=2, **kw):
    """bed_height for every friction, `processes` at a time."""
    with Pool(processes) as pool:
        return pool.starmap(bed_height, [(mu, kw.get("n", 2000), kw.get("steps", 30000)) for mu in frictions])


def main():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t0 = time.time()
    results = sweep(FRICTIONS)
    heights = [h for h, _ in results]
    for mu, (h, ke) in zip(FRICTIONS, results):
        print(f"friction {mu:4.2f}: bed height {1000 * h:6.2f} mm (kinetic energy {ke:.2e} J)")
    print(f"{len(FRICTIONS)} runs in {time.time() - t0:.0f} s")
    fig, ax = plt.subplots(figsize=(5, 3.5))
    ax.plot(FRICTIONS, [1000 * h for h in heights], "o-")
    ax.set_xlabel("coefficient of friction")
    ax.set_ylabel("bed height (mm)")
    ax.set_title("2000 beads of 1 mm poured into a 20 mm box")
    fig.tight_layout()
    fig.savefig("bed_height.png", dpi=120)
    print("wrote bed_height.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
