#!/usr/bin/env python3
"""Helper of scripts/parity.sh (standard library only).

  parity.py reseed FILE VARIANT [--count]
      Replaces the random seeds of a LIGGGHTS script in place with other primes (VARIANT
      1 to 8 picks the set) and prints how many it replaced; with --count it only counts
      and writes nothing. The seeds are the `seed N` of each `fix ... insert/*` and the
      first number after `particletemplate/*` and `particledistribution/*`.

  parity.py table SCRATCH --budget S --commit C --liggghts V --rdem R --nproc N [--pattern P]
      Reads the runs parity.sh left in SCRATCH (one folder per script, holding `name` and
      the runs lig0, rdem, lig1, lig2, rdem1, rdem2, and for a second look lig3..lig8 and
      rdem3..rdem8, each with out, err, rc and secs) and prints the markdown page: a header
      saying how agreement is judged, then the table.

  parity.py verdict DIR --budget S
      Prints the verdict of one script's folder DIR from the runs it holds so far
      (`agree`, or why not); parity.sh asks it whether a second look is due.
"""
import argparse
import datetime
import math
import os
import re
import sys

# --- seeds -----------------------------------------------------------------------------

# LIGGGHTS 3.8 wants each seed to be a prime > 10000; the seeds of one script must differ
# from each other. Variant k gives its i-th seed the i-th prime from BASES[k] on.
BASES = {
    1: 49979687,
    2: 86028121,
    # The sets of the second look (see SECOND_LOOK).
    3: 15485867,
    4: 32452843,
    5: 67867967,
    6: 23879519,
    7: 57885161,
    8: 73856093,
}
# Seed sets of the second look: a seeded script whose verdict on the first three
# LIGGGHTS runs is not `agree` is run with these too, by both programs.
SECOND_LOOK = (3, 4, 5, 6, 7, 8)


def is_prime(n):
    if n < 2:
        return False
    if n % 2 == 0:
        return n == 2
    f = 3
    while f * f <= n:
        if n % f == 0:
            return False
        f += 2
    return True


def primes_from(n):
    while True:
        if is_prime(n):
            yield n
        n += 1


def commands(lines):
    """Groups script lines into commands (a line ending with `&` continues on the next)."""
    i = 0
    while i < len(lines):
        j = i
        while j + 1 < len(lines) and lines[j].split("#")[0].rstrip().endswith("&"):
            j += 1
        yield i, j + 1
        i = j + 1


def reseed(text, variant):
    """The script with its seeds replaced, and how many were replaced."""
    primes = primes_from(BASES[variant])
    lines = text.split("\n")
    count = 0
    for i, j in commands(lines):
        words = " ".join(l.split("#")[0].replace("&", " ") for l in lines[i:j]).split()
        if len(words) < 5 or words[0] != "fix":
            continue
        style = words[3]
        if style.startswith("insert/"):
            rx = re.compile(r"(\bseed(?:\s|&)+)(\d+)\b")
        elif style.startswith(("particletemplate/", "particledistribution/")):
            rx = re.compile(r"(" + re.escape(style) + r"(?:\s|&)+)(\d+)\b")
        else:
            continue
        block, n = rx.subn(lambda m: m.group(1) + str(next(primes)), "\n".join(lines[i:j]), 1)
        if n:
            lines[i:j] = block.split("\n")
            count += 1
    return "\n".join(lines), count


def cmd_reseed(a):
    with open(a.file) as f:
        text, count = reseed(f.read(), a.variant)
    if not a.count:
        with open(a.file, "w") as f:
            f.write(text)
    print(count)


# --- reading one run -------------------------------------------------------------------


def read(path, default=""):
    try:
        with open(path, errors="replace") as f:
            return f.read()
    except OSError:
        return default


def error_line(out, err):
    """The first line of the error a run printed, with where it is, if it says."""
    for text in (err, out):
        lines = text.splitlines()
        for k, line in enumerate(lines):
            s = line.strip()
            if "ERROR" in s:  # LIGGGHTS: "ERROR: ..." or "ERROR on proc 0: ..."
                return re.sub(r"^ERROR( on proc \d+)?:\s*", "", s)
            if s.startswith("×"):  # rdem: "× message", wrapped on "│ ..." lines
                msg = s[1:].strip()
                for more in lines[k + 1 :]:
                    m = more.strip()
                    if m.startswith("│"):
                        msg += " " + m[1:].strip()
                        continue
                    loc = re.search(r"╭─\[([^\]]+?):(\d+):\d+\]", m)
                    if loc:
                        msg += f" ({loc.group(1)}:{loc.group(2)})"
                    break
                return msg
    lines = [l.strip() for l in err.splitlines() if l.strip()]
    return lines[-1] if lines else ""


def thermo(out):
    """The last thermo header (list of names) and the last row under it (list of strings)."""
    head, last_head, last_row = None, None, None
    for line in out.splitlines():
        w = line.split()
        if w[:1] == ["Step"]:
            head = w
            continue
        if head and len(w) == len(head):
            try:
                [float(x) for x in w]
            except ValueError:
                continue
            last_head, last_row = head, w
        elif w[:1] == ["Loop"]:
            head = None
    return last_head, last_row


class Run:
    """One program's run of one script: status, seconds, atoms and last thermo row."""

    def __init__(self, d, budget):
        self.present = os.path.isdir(d)
        out, err = read(os.path.join(d, "out")), read(os.path.join(d, "err"))
        rc = read(os.path.join(d, "rc"), "-1").strip()
        self.secs = float(read(os.path.join(d, "secs"), "nan") or "nan")
        self.head, self.row = thermo(out)
        if rc in ("124", "137"):
            self.status = f"timeout (> {budget} s)"
        elif rc != "0":
            signal = f" (signal {int(rc) - 128})" if rc.isdigit() and int(rc) > 128 else ""
            self.status = "error: " + (error_line(out, err) or f"exit code {rc}{signal}")
        elif not self.row:
            self.status = "error: no thermo row printed"
        else:
            self.status = "ran"
        self.ok = self.status == "ran"
        # Atom count at the end: the last "Loop time ... with N atoms", else the Atoms column.
        loops = re.findall(r"^Loop time of .* with (\d+) atoms", out, re.M)
        self.atoms = int(loops[-1]) if loops else None
        if self.atoms is None and self.row and "Atoms" in self.head:
            self.atoms = int(float(self.row[self.head.index("Atoms")]))
        self.cols = {}  # column name (made unique) -> printed value
        if self.row:
            for name, v in zip(self.head, self.row):
                key, k = name, 2
                while key in self.cols:
                    key, k = f"{name}#{k}", k + 1
                self.cols[key] = v


# --- comparing -------------------------------------------------------------------------

TIMING = ("CPU", "T/CPU", "S/CPU")  # thermo's cpu, tpcpu, spcpu: shown, not compared
REL_TOL = 1e-6  # one LIGGGHTS value (or three identical ones): this relative tolerance
FLOOR = 1e-9  # the spread is at least [min, max] widened by FLOOR * max |value|
# Student's t, two-sided 95 %, for n - 1 degrees of freedom (n LIGGGHTS runs).
T95 = {1: 12.706, 2: 4.303, 3: 3.182, 4: 2.776, 5: 2.571, 6: 2.447, 7: 2.365, 8: 2.306}


def spread(values):
    """LIGGGHTS' spread of one column from its n runs: the 95 % prediction interval of one
    more run, mean ± t(0.975, n − 1) · s · √(1 + 1/n), with s the sample standard
    deviation (so a run of the same distribution falls outside it 1 time in 20 if the
    values are normal). [min, max] alone would reject such a run half of the time for
    n = 3 (P(outside the range of 3 draws) = 2/4)."""
    lo, hi = min(values), max(values)
    if lo == hi:
        w = REL_TOL * abs(lo)
        return lo - w, hi + w
    n = len(values)
    mean = sum(values) / n
    s = math.sqrt(sum((v - mean) ** 2 for v in values) / (n - 1))
    half = T95[n - 1] * s * math.sqrt(1 + 1 / n)
    floor = FLOOR * max(abs(lo), abs(hi))
    return min(lo, mean - half) - floor, max(hi, mean + half) + floor


def fmt(x):
    return f"{x:.4g}"


def pct(x):
    return f"{x:+.0f} %" if abs(x) >= 10 else f"{x:+.2g} %"


def verdict(ligs, r):
    """`agree`, or the reasons rdem's run does not agree with LIGGGHTS' runs `ligs`."""
    l0 = ligs[0]
    if l0.status.startswith("timeout"):
        return "LIGGGHTS runs longer than the budget"
    if not l0.ok:
        return "LIGGGHTS cannot run it"
    if not r.ok:
        return "rdem " + r.status.split(":")[0]
    why = []
    # Atom count: within max(2, 1 %) of LIGGGHTS' range.
    counts = [l.atoms for l in ligs if l.atoms is not None]
    lo, hi = min(counts), max(counts)
    tol = max(2, 0.01 * hi)
    if r.atoms is None or not (lo - tol <= r.atoms <= hi + tol):
        ref = str(lo) if lo == hi else f"{lo}..{hi}"
        why.append(f"atoms {r.atoms} vs {ref} (allowed ±{tol:g})")
    for name, v0 in l0.cols.items():
        if name == "Atoms" or name in TIMING:
            continue
        if name not in r.cols:
            why.append(f"rdem prints no {name} column")
            continue
        v = float(r.cols[name])
        if name == "Step":
            if v != float(v0):
                why.append(f"Step {r.cols[name]} vs {v0}")
            continue
        values = [float(l.cols[name]) for l in ligs if name in l.cols]
        lo, hi = spread(values)
        if not (lo <= v <= hi) or math.isnan(v):
            bound = hi if v > hi else lo
            off = pct(100 * (v - bound) / abs(bound)) if bound else f"{v - bound:+.3g}"
            rng = fmt(values[0]) if len(set(values)) == 1 else f"{fmt(min(values))}..{fmt(max(values))}"
            why.append(f"{name} {fmt(v)} vs {rng} ({off} off)")
    return "agree" if not why else "; ".join(why)


def spread_verdict(ligs, rdems):
    """`overlap`, or the columns where rdem's seed runs `rdems` and LIGGGHTS' runs `ligs`
    do not overlap: rdem's [min, max] against LIGGGHTS' spread (as in `verdict`), and the
    atom ranges within max(2, 1 %)."""
    why = []
    counts = [l.atoms for l in ligs if l.atoms is not None]
    rcounts = [r.atoms for r in rdems if r.atoms is not None]
    tol = max(2, 0.01 * max(counts))
    if not rcounts or min(rcounts) > max(counts) + tol or max(rcounts) < min(counts) - tol:
        why.append(f"atoms {rng(rcounts)} vs {rng(counts)}")
    for name, v0 in ligs[0].cols.items():
        if name in ("Atoms", "Step") or name in TIMING:
            continue
        values = [float(l.cols[name]) for l in ligs if name in l.cols]
        mine = [float(r.cols[name]) for r in rdems if name in r.cols]
        lo, hi = spread(values)
        if not mine or any(math.isnan(v) for v in mine) or min(mine) > hi or max(mine) < lo:
            why.append(f"{name} {rng(mine, fmt)} vs {rng(values, fmt)}")
    return "overlap" if not why else "; ".join(why)


def rng(values, f=str):
    """`a` or `a..b`: the range of `values`."""
    if not values:
        return "none"
    lo, hi = min(values), max(values)
    return f(lo) if lo == hi else f"{f(lo)}..{f(hi)}"


# --- the page --------------------------------------------------------------------------


def cell(s):
    s = s.replace("|", "\\|")
    return s if len(s) <= 160 else s[:157] + "..."


def row_text(run):
    if not run.ok:  # a run that stopped early: its last row is not the end
        return ""
    return " ".join(f"{k}={v}" for k, v in run.cols.items() if k != "Atoms")


class Script:
    """One script's runs in its scratch folder `d`: LIGGGHTS' (`ligs`, the ones that ran)
    and rdem's (`rdems`), the first of each (`l0`, `r`), and the verdicts."""

    def __init__(self, d, budget):
        self.name = read(os.path.join(d, "name")).strip()
        self.l0 = Run(os.path.join(d, "lig0"), budget)
        self.r = Run(os.path.join(d, "rdem"), budget)
        if self.l0.status.startswith("timeout"):
            self.r.status = self.l0.status  # rdem is not run then: both are marked timeout
        extra = ("1", "2") + tuple(str(k) for k in SECOND_LOOK)
        self.seeds = [Run(os.path.join(d, "lig" + k), budget) for k in extra]
        self.seeds = [s for s in self.seeds if s.present]
        self.ligs = [self.l0] + [s for s in self.seeds if s.ok]
        rseeds = [Run(os.path.join(d, "rdem" + k), budget) for k in extra]
        rseeds = [s for s in rseeds if s.present]
        self.rdems = [self.r] + [s for s in rseeds if s.ok]
        # The second look ran: LIGGGHTS' runs beyond its first three.
        self.second = os.path.isdir(os.path.join(d, f"lig{SECOND_LOOK[0]}"))
        self.verdict = verdict(self.ligs, self.r)
        both = len(self.ligs) > 1 and len(self.rdems) > 1 and self.l0.ok and self.r.ok
        self.spreads = spread_verdict(self.ligs, self.rdems) if both else ""


def cmd_verdict(a):
    print(Script(a.dir, a.budget).verdict)


def cmd_table(a):
    rows, tally, tally2, second = [], {}, {}, []
    for sub in sorted(os.listdir(a.scratch)):
        d = os.path.join(a.scratch, sub)
        if not os.path.isfile(os.path.join(d, "name")):
            continue
        sc = Script(d, a.budget)
        name, l0, r, seeds, ligs, rdems = sc.name, sc.l0, sc.r, sc.seeds, sc.ligs, sc.rdems
        v, v2 = sc.verdict, sc.spreads
        if v2:
            tally2[v2 == "overlap"] = tally2.get(v2 == "overlap", 0) + 1
        if sc.second:
            second.append(name)
        notes = [f"LIGGGHTS run {k + 2}: {s.status}" for k, s in enumerate(seeds) if not s.ok]
        agrees = v == "agree"
        if notes:
            v += " (" + "; ".join(notes) + f"; the spread is that of {len(ligs)} runs)"
        kind = (
            "agree" if agrees
            else "LIGGGHTS timeout" if l0.status.startswith("timeout")
            else "LIGGGHTS error" if not l0.ok
            else "rdem error/timeout" if not r.ok
            else "disagree"
        )
        tally[kind] = tally.get(kind, 0) + 1
        ratio = fmt(l0.secs / r.secs) if l0.ok and r.ok and r.secs > 0 else ""
        rows.append(
            [
                name,
                l0.status,
                r.status,
                str(l0.atoms) if l0.ok and l0.atoms is not None else "",
                str(r.atoms) if r.ok and r.atoms is not None else "",
                row_text(l0),
                row_text(r),
                str(len(ligs)) if l0.ok else "",
                str(len(rdems)) if r.ok else "",
                ratio,
                v,
                v2,
            ]
        )

    now = datetime.datetime.now().astimezone().strftime("%Y-%m-%d %H:%M %Z")
    order = ["agree", "disagree", "rdem error/timeout", "LIGGGHTS error", "LIGGGHTS timeout"]
    summary = ", ".join(f"{k}: {tally[k]}" for k in order if k in tally)
    print(f"""# Parity with LIGGGHTS 3.8 on its tutorials

Made by `scripts/parity.sh` (run it again to refresh this page).

- Date: {now}
- rdem commit: {a.commit}; binary: `{a.rdem}`
- LIGGGHTS: {a.liggghts}
- Machine: {a.nproc} cores (`nproc`), load average {a.load} at the start; each run on 1 core (rdem `--threads 1`, LIGGGHTS 1 process), one run at a time
- Budget: {a.budget} s of wall time per run{f"; scripts matching `{a.pattern}` only" if a.pattern else ""}
- Result: {summary}
- Seed spreads (scripts with seeds that both ran): overlap {tally2.get(True, 0)}, apart {tally2.get(False, 0)}
- Second look ({len(SECOND_LOOK)} more seed sets each): {", ".join(second) if second else "none was due"}

Each `in.*` script of `Tutorials_public/*/` runs unmodified from a fresh copy of its
folder (`-in SCRIPT -log none`). LIGGGHTS also runs it twice more with other seeds: every
`seed N` of a `fix insert/*` and the first number after `particletemplate/*` and
`particledistribution/*` replaced by other primes (from {BASES[1]} and {BASES[2]} on).
All three kinds are replaced because rdem draws positions, template choices and
multisphere mass properties from its own random generator, so none of LIGGGHTS' random
sequences carries over to rdem. A script without seeds is run twice more by LIGGGHTS on
2 and 3 MPI processes instead: only the order of its sums differs, which a chaotic run
grows into another end state. The columns "last thermo" are the last thermo row of the
last run (names from the last `Step` header); atoms is the count of the last `Loop time`
line. "LIG runs" is the number of LIGGGHTS runs that gave the spread; "time L/R" is
LIGGGHTS' wall time over rdem's (first seed).

rdem agrees with LIGGGHTS when
- the atom count is within max(2, 1 %) of the range of LIGGGHTS' counts;
- the last thermo row has the same Step;
- every other column of that row (but the timings CPU, T/CPU, S/CPU) lies in LIGGGHTS' spread:
  the 95 % prediction interval of one more LIGGGHTS run from its three, mean ± t · s · √(1 + 1/3)
  with s their sample standard deviation and t = {T95[2]} (Student, 2 degrees of freedom),
  and never narrower than [min, max] widened by {FLOOR:g} × max |value|. Where the three
  values are identical (a constant such as a volume) or there is one LIGGGHTS run, the
  spread is that value ± {REL_TOL:g} × |value|.

Why not [min, max] of the three: a fourth draw of the same distribution falls outside
the range of three draws half of the time, so that test calls half of the agreeing
random columns off (the table of 2026-12-04 used it, widened by 10 %, and judged 12 rows
apart whose seed spreads met). The prediction interval misses such a draw 1 time in 20
when the values are normal. It is wide, because three runs say little of a spread; the
"spreads" column below is the second look.

The last column compares the two programs' seed spreads: rdem also runs the script with
the two other seed sets, and the spreads overlap when, for the atom count and each column,
rdem's [min, max] over its runs meets LIGGGHTS' spread (as above; atoms within max(2, 1 %)).
It says nothing finer than three draws of each can. (Without seeds rdem runs once: its
results do not depend on the thread count.)

The second look: three LIGGGHTS runs estimate their spread poorly (a column whose three
values happen to lie close together gives a narrow interval), so a script with seeds whose
verdict is not `agree` after the first three LIGGGHTS runs is run by both programs with
{len(SECOND_LOOK)} more seed sets (from {", ".join(str(BASES[k]) for k in SECOND_LOOK)} on). Its verdict is then
judged as above, on rdem's first run against the prediction interval of all of LIGGGHTS'
runs (t for their number less one), and the spreads on all runs of each program. The
rule is the same for every script, and the "LIG runs" column shows which had it.

A script LIGGGHTS cannot run shows LIGGGHTS' error; one LIGGGHTS does not finish within
the budget is marked timeout for both and rdem is not run. Otherwise the verdict says
which column is off, rdem's value against LIGGGHTS' (range of) values, and by how much
relative to the nearest end of the spread.
""")
    heads = ["script", "LIGGGHTS", "rdem", "atoms L", "atoms R", "last thermo L",
             "last thermo R", "LIG runs", "rdem runs", "time L/R", "verdict", "spreads"]
    print("| " + " | ".join(heads) + " |")
    print("|" + "|".join("---" for _ in heads) + "|")
    for r in rows:
        print("| " + " | ".join(cell(c) for c in r) + " |")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="cmd", required=True)
    s = sub.add_parser("reseed")
    s.add_argument("file")
    s.add_argument("variant", type=int, choices=sorted(BASES))
    s.add_argument("--count", action="store_true")
    s.set_defaults(func=cmd_reseed)
    t = sub.add_parser("table")
    t.add_argument("scratch")
    for opt in ("budget", "commit", "liggghts", "rdem", "nproc", "load", "pattern"):
        t.add_argument("--" + opt, default="")
    t.set_defaults(func=cmd_table)
    v = sub.add_parser("verdict")
    v.add_argument("dir")
    v.add_argument("--budget", default="")
    v.set_defaults(func=cmd_verdict)
    a = p.parse_args()
    a.func(a)


if __name__ == "__main__":
    sys.exit(main())
