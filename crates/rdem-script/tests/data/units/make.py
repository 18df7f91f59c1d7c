"""Writes cgs.in and micro.in: si.in with every number converted (lengths, masses and
times scaled by L, M, T), so that the three runs are one motion in three unit systems."""

SRC = open("si.in").read()


def convert(name, L, M, T):
    s = SRC.replace("units si", "units " + name)
    P = M / (L * T * T)  # pressure (Young's modulus)
    rep = {
        "-0.05 0.05 -0.05 0.05 0 0.1": f"{-0.05*L:g} {0.05*L:g} {-0.05*L:g} {0.05*L:g} 0 {0.1*L:g}",
        "neighbor 0.002": f"neighbor {0.002*L:g}",
        "youngsModulus peratomtype 5.e6": f"youngsModulus peratomtype {5e6*P:g}",
        "timestep 0.00001": f"timestep {1e-5*T:g}",
        "gravity 9.81": f"gravity {9.81*L/T/T:g}",
        "single 0.0 0.0 0.02": f"single 0.0 0.0 {0.02*L:g}",
        "single 0.0031 0.0005 0.05": f"single {0.0031*L:g} {0.0005*L:g} {0.05*L:g}",
        "diameter 0.01 density 2500": f"diameter {0.01*L:g} density {2500*M/L**3:g}",
        "diameter 0.008 density 2500": f"diameter {0.008*L:g} density {2500*M/L**3:g}",
        "set 0.1 0 0": f"set {0.1*L/T:g} 0 0",
    }
    for k, v in rep.items():
        assert k in s, k
        s = s.replace(k, v)
    open(name + ".in", "w").write(s)


convert("cgs", 100.0, 1000.0, 1.0)
convert("micro", 1e6, 1e15, 1e6)
