"""Reading a `.pvd` series of rdem's VTK dumps into numpy, with meshio.

Every VTK dump series rdem writes (a file name with `*`) comes with a ParaView
collection, `post/name.pvd`, listing each snapshot's file and time. This example runs a
short pour with `dump custom/vtk` as XML UnstructuredGrid (`.vtu`, which meshio reads; it
does not read legacy VTK polydata), then reads the collection: the times from the `.pvd`
(plain XML), each snapshot's points and point data with meshio, and prints how the bed's
mean height and kinetic energy evolve. (The dump starts after the insertion step: meshio
cannot read a compressed snapshot with no particles; `first yes` writes step 1, which is
no multiple of 2000.)

    python examples/python/read_pvd.py

Needs the rdem package (pip install . from the repository root) and meshio. The same
`read_series` reads LIGGGHTS' own VTK dumps given a `.pvd` for them.
"""

import os
import sys
import tempfile
import xml.etree.ElementTree as ET

import meshio
import numpy as np

import rdem

POUR = """\
atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
region box block 0 0.02 0 0.02 0 0.06 units box
create_box 1 box
neighbor 0.0004 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 5e6
fix m2 all property/global poissonsRatio peratomtype 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.3
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 1e-5
fix gravi all gravity 9.81 vector 0 0 -1
fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0
fix sides all wall/gran model hertz tangential history primitive type 1 zcylinder 0.0095 0.01 0.01
region ins cylinder z 0.01 0.01 0.008 0.01 0.058 units box
fix pts all particletemplate/sphere 15485863 atom_type 1 density constant 2500 radius constant 0.0005
fix pdd all particledistribution/discrete 32452843 1 pts 1.0
fix ins all insert/pack seed 49979687 distributiontemplate pdd insert_every once overlapcheck yes all_in yes particles_in_region 500 region ins
fix integr all nve/sphere
run 1
dump d all custom/vtk 2000 post/bed_*.vtu id type radius mass vx vy vz
dump_modify d first yes
run 15999
"""


def read_series(pvd):
    """[(time, points (n×3), {name: point data})] of the snapshots a .pvd lists, in order."""
    root = ET.parse(pvd).getroot()
    folder = os.path.dirname(pvd)
    series = []
    for ds in root.iter("DataSet"):
        mesh = meshio.read(os.path.join(folder, ds.get("file")))
        series.append((float(ds.get("timestep")), np.asarray(mesh.points), dict(mesh.point_data)))
    return sorted(series, key=lambda s: s[0])


def kinetic_energy(data):
    """Translational kinetic energy of one snapshot's point data (mass and velocity: the
    vector field "v", or vx, vy, vz)."""
    v = np.column_stack([data[k] for k in ("vx", "vy", "vz")]) if "vx" in data else data["v"]
    return 0.5 * np.sum(np.ravel(data["mass"]) * np.sum(v**2, axis=1))


def main():
    with tempfile.TemporaryDirectory() as d:
        os.chdir(d)
        sim = rdem.Simulation()
        sim.commands(POUR)
        series = read_series("post/bed.pvd")
    print("    time (s)  particles  mean z (mm)  kinetic energy (J)")
    for t, x, data in series:
        print(f"{t:12.3f} {len(x):10d} {1000 * x[:, 2].mean():12.3f} {kinetic_energy(data):19.3e}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
