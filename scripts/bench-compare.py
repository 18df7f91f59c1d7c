#!/usr/bin/env python3
"""rdem against LIGGGHTS 3.8 (and LAMMPS when installed), interleaved, with medians.

Runs the benchmark cases of ../shared/bench in rounds, every configuration once per
round in turn (A B C A B C ...), so that a machine that slows down or speeds up during
the session weighs on every program alike. Each run's figure is particle-steps per
second of its last "Loop time of T on P procs for N steps with M atoms" line (M*N/T, as
shared/bench/compare.sh computes it); for single-process runs the peak resident memory
(GNU time's maximum RSS) and rdem's own "Memory usage per processor" figure are taken too.

Cases:
  dense    the settled dense bed (8656 spheres, 5000 steps): in.dense_data, and
           in.dense_data.lmp for LAMMPS;
  lattice  1,000,000 spheres settling from a simple cubic lattice (200 steps):
           in.lattice (-var n N for another size; no LAMMPS script);
  clumps   2301 rigid dumbbells (4602 spheres, fix multisphere) settling in a box, 4000
           steps after 8000 of filling: scripts/bench/in.clump_bed (no rdem 2-rank run:
           rdem runs clumps on one rank so far; no LAMMPS script).
Configurations: rdem with 1 and 2 threads and with 2 MPI ranks of 1 thread each (when the
binary is built with the `mpi` feature and mpirun exists), LIGGGHTS on 1 and 2 ranks,
LAMMPS on 1 rank (dense only, when `lmp` or `lmp_serial` is installed).

Prints every run as it ends, then per case the median of each configuration and the
ratios rdem/reference of every round and of the medians.

    cargo build --release --features rdem-cli/mpi
    python3 scripts/bench-compare.py                       # both cases, 3 rounds
    python3 scripts/bench-compare.py --cases dense --rounds 5
    python3 scripts/bench-compare.py --cases lattice --n 50 --rounds 1
    python3 scripts/bench-compare.py --cases clumps --rounds 3
"""

import argparse
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
LOOP = re.compile(r"^Loop time of (\S+) on \d+ procs for (\d+) steps with (\d+) atoms", re.M)
MEMORY = re.compile(r"Memory usage per processor = (\S+) Mbytes")


def rate_of(text):
    """Particle-steps per second of the last Loop time line, or None."""
    found = LOOP.findall(text)
    if not found:
        return None
    t, n, m = found[-1]
    t = float(t)
    return int(m) * int(n) / t if t > 0 else None


def run(cmd, cwd, env=None, measure_rss=True):
    """Runs cmd in cwd; returns (rate, peak RSS in MiB or None, printed MiB or None)."""
    rss_file = os.path.join(cwd, ".rss")
    measure_rss = measure_rss and os.path.exists("/usr/bin/time")
    full = ["/usr/bin/time", "-f", "%M", "-o", rss_file] + cmd if measure_rss else cmd
    e = dict(os.environ)
    e.update(env or {})
    p = subprocess.run(full, cwd=cwd, env=e, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    rate = rate_of(p.stdout)
    if p.returncode != 0 or rate is None:
        tail = "\n".join(p.stdout.splitlines()[-15:])
        sys.exit(f"failed: {' '.join(cmd)} (exit {p.returncode})\n{tail}")
    rss = None
    if measure_rss and os.path.exists(rss_file):
        with open(rss_file) as f:
            words = f.read().split()
        rss = int(words[-1]) / 1024 if words else None
        os.remove(rss_file)
    printed = MEMORY.findall(p.stdout)
    return rate, rss, float(printed[-1]) if printed else None


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--cases", default="dense,lattice")
    ap.add_argument("--n", type=int, default=100, help="lattice edge (n^3 spheres)")
    ap.add_argument("--rdem", default=os.path.join(ROOT, "target", "release", "rdem"))
    ap.add_argument("--bench", default=os.path.join(ROOT, "..", "shared", "bench"))
    ap.add_argument("--no-ranks", action="store_true", help="skip the 2-rank runs")
    args = ap.parse_args()

    rdem = os.path.abspath(args.rdem)
    if not os.access(rdem, os.X_OK):
        sys.exit(f"no rdem binary at {rdem}: cargo build --release --features rdem-cli/mpi")
    liggghts = shutil.which("liggghts")
    if not liggghts:
        sys.exit("LIGGGHTS not found: ../shared/reference/setup-liggghts.sh installs it")
    lammps = shutil.which("lmp") or shutil.which("lmp_serial")
    mpirun = shutil.which("mpirun")
    mpi = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", "2"]
    has_mpi = False
    if mpirun and not args.no_ranks:
        info = subprocess.run([rdem, "--version"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        has_mpi = "mpi" in info.stdout.lower()
        if not has_mpi:
            print("note: this rdem is built without MPI; the rdem 2-rank runs are left out", file=sys.stderr)

    work = tempfile.mkdtemp(prefix="rdem-bench-")
    try:
        for src in os.listdir(args.bench):
            if src.startswith("in.") or src.endswith(".data"):
                shutil.copy(os.path.join(args.bench, src), work)
        shutil.copy(os.path.join(HERE, "bench", "in.clump_bed"), work)
        one = {"RDEM_THREADS": "1", "OMP_NUM_THREADS": "1"}
        two = {"RDEM_THREADS": "2", "OMP_NUM_THREADS": "1"}
        for case in args.cases.split(","):
            if case == "dense":
                script, extra = "in.dense_data", []
            elif case == "lattice":
                script, extra = "in.lattice", ["-var", "n", str(args.n)]
            elif case == "clumps":
                script, extra = "in.clump_bed", []
            else:
                sys.exit(f"unknown case {case!r}: dense, lattice or clumps")
            rdem_ranks = case != "clumps"
            configs = [
                ("rdem 1 thread", [rdem, "-in", script, "-log", "none"] + extra, one, True),
                ("rdem 2 threads", [rdem, "-in", script, "-log", "none"] + extra, two, True),
            ]
            if has_mpi and rdem_ranks:
                configs.append(("rdem 2 ranks", mpi + [rdem, "-in", script, "-log", "none"] + extra, one, False))
            configs.append(("LIGGGHTS 1 rank", [liggghts, "-in", script, "-log", "none"] + extra, one, True))
            if mpirun and not args.no_ranks:
                configs.append(("LIGGGHTS 2 ranks", mpi + [liggghts, "-in", script, "-log", "none"] + extra, one, False))
            if lammps and case == "dense":
                configs.append(("LAMMPS 1 rank", [lammps, "-in", script + ".lmp", "-log", "none"], one, True))
            size = f" (n = {args.n})" if case == "lattice" else ""
            print(f"== {case}{size}: {args.rounds} rounds of {', '.join(c[0] for c in configs)}", flush=True)
            results = {c[0]: [] for c in configs}
            for r in range(args.rounds):
                for name, cmd, env, rss in configs:
                    got = run(cmd, work, env, rss)
                    results[name].append(got)
                    mem = ""
                    if got[1] is not None:
                        mem = f"  peak RSS {got[1]:.0f} MiB"
                    if got[2] is not None:
                        mem += f"  printed {got[2]:.0f} MiB"
                    print(f"round {r + 1}  {name:<17} {got[0]:.4g} particle-steps/s{mem}", flush=True)
            report(case, results)
    finally:
        shutil.rmtree(work, ignore_errors=True)


def report(case, results):
    med = {k: statistics.median(x[0] for x in v) for k, v in results.items()}
    print(f"-- {case}: medians")
    for k, m in med.items():
        rss = [x[1] for x in results[k] if x[1] is not None]
        extra = f"  peak RSS {statistics.median(rss):.0f} MiB" if rss else ""
        printed = [x[2] for x in results[k] if x[2] is not None]
        if printed:
            extra += f"  printed {statistics.median(printed):.0f} MiB"
        print(f"   {k:<17} {m:.4g}{extra}")
    pairs = [
        ("rdem 1 thread", "LIGGGHTS 1 rank"),
        ("rdem 1 thread", "LAMMPS 1 rank"),
        ("rdem 2 threads", "LIGGGHTS 2 ranks"),
        ("rdem 2 ranks", "LIGGGHTS 2 ranks"),
        ("rdem 2 threads", "rdem 1 thread"),
        ("rdem 2 ranks", "rdem 1 thread"),
    ]
    print(f"-- {case}: ratios (per round; of the medians)")
    for a, b in pairs:
        if a in results and b in results:
            per = [x[0] / y[0] for x, y in zip(results[a], results[b])]
            rounds = " ".join(f"{q:.2f}" for q in per)
            print(f"   {a + ' / ' + b:<36} {rounds}   median {med[a] / med[b]:.2f}")
    if "rdem 1 thread" in results and "LIGGGHTS 1 rank" in results:
        ra = [x[1] for x in results["rdem 1 thread"] if x[1] is not None]
        rb = [x[1] for x in results["LIGGGHTS 1 rank"] if x[1] is not None]
        if ra and rb:
            print(f"   peak RSS rdem / LIGGGHTS (1 process)  {statistics.median(ra) / statistics.median(rb):.2f}")
    sys.stdout.flush()


if __name__ == "__main__":
    main()
