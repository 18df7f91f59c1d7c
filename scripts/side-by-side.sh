#!/usr/bin/env bash
# Runs one case of ../shared/wild with rdem and with LIGGGHTS 3.8 (`liggghts` on the PATH)
# from scratch copies of its folder, after the same edits to its main script in both
# copies (to shorten runs or print thermo more often), and prints their thermo rows side
# by side with the relative difference of each column. Not part of CI: it is how the
# figures in the issue notes were made.
#
# Usage: scripts/side-by-side.sh CASE-PATTERN LIGGGHTS-RANKS [SED-EXPRESSION...]
#   e.g. scripts/side-by-side.sh 36_thesis 6 's/^run\t\${fillsteps}/run 200000/'
# Environment: RDEM (default target/release/rdem), RDEM_RANKS (default 1: rdem warns
# about a `processors` grid that does not fit and uses one that does), KEEP=1 keeps
# the scratch folder, BASELINE='SED-EXPRESSION' also runs LIGGGHTS on a third copy with
# that extra edit (another insertion seed) and prints how far LIGGGHTS is from itself:
# the yardstick for "within LIGGGHTS' own randomness".
set -uo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
pattern="$1"
np="$2"
shift 2
rdem="$(realpath "${RDEM:-$here/target/release/rdem}")"
wild="$(realpath "$here/../shared/wild")"
line=$(tail -n +2 "$wild/MANIFEST.tsv" | grep -m1 "^[^	]*$pattern")
[ -n "$line" ] || { echo "no case matches '$pattern'"; exit 2; }
case_dir=$(cut -f1 <<<"$line")
main=$(cut -f2 <<<"$line")
top="${case_dir%%/*}"
scratch="$(mktemp -d /tmp/rdem-sbs.XXXXXX)"
[ "${KEEP:-0}" = 1 ] || trap 'rm -rf "$scratch"' EXIT
runs="rdem liggghts"
[ -n "${BASELINE:-}" ] && runs="$runs baseline"
for who in $runs; do
  cp -r "$wild/$top" "$scratch/$who"
  script="$scratch/$who/${case_dir#"$top"}/$main"
  for e in "$@"; do sed -i -e "$e" "$script"; done
  [ "$who" = baseline ] && sed -i -e "$BASELINE" "$script"
done
run_one() {
  local who="$1"
  cd "$scratch/$who/${case_dir#"$top"}" || exit 2
  local start
  start=$(date +%s.%N)
  if [ "$who" = rdem ]; then
    if [ "${RDEM_RANKS:-1}" = 1 ]; then
      "$rdem" -in "$main" -log log.txt >stdout.txt 2>stderr.txt </dev/null
    else
      mpirun --oversubscribe --allow-run-as-root -np "$RDEM_RANKS" "$rdem" -in "$main" \
        -log log.txt >stdout.txt 2>stderr.txt </dev/null
    fi
  elif [ "$np" = 1 ]; then
    liggghts -in "$main" -log log.txt >stdout.txt 2>stderr.txt </dev/null
  else
    mpirun --oversubscribe --allow-run-as-root -np "$np" liggghts -in "$main" -log log.txt \
      >stdout.txt 2>stderr.txt </dev/null
  fi
  local status=$?
  echo "$who: exit $status in $(echo "$(date +%s.%N) - $start" | bc | cut -c1-7) s"
  [ $status -eq 0 ] || tail -n 5 stderr.txt stdout.txt
}
for who in $runs; do run_one "$who"; done
outs=()
for who in $runs; do outs+=("$scratch/$who/${case_dir#"$top"}/stdout.txt"); done
python3 - "${outs[@]}" <<'EOF'
import sys

def tables(path):
    """Thermo rows of a LIGGGHTS-style screen output: {step: {column: value}}, last row wins."""
    rows, head = {}, None
    for line in open(path, errors="replace"):
        w = line.split()
        if w and w[0] == "Step":
            head = w
            continue
        if head and len(w) == len(head):
            try:
                vals = [float(x) for x in w]
            except ValueError:
                head = None
                continue
            rows[int(vals[0])] = dict(zip(head, vals))
        elif head and w[:1] == ["Loop"]:
            head = None
    return rows

def rel(a, b):
    m = max(abs(a), abs(b))
    return abs(a - b) / m if m > 0 else 0.0

r, l = tables(sys.argv[1]), tables(sys.argv[2])
base = tables(sys.argv[3]) if len(sys.argv) > 3 else None
steps = sorted(set(r) & set(l) & (set(base) if base is not None else set(l)))
if not steps:
    sys.exit("no common thermo steps")
cols = [c for c in l[steps[0]] if c != "Step" and c in r[steps[0]]]
extra = lambda c: f" {'LIG2 rel':>8}" if base is not None else ""
print(f"{'step':>10} " + " ".join(f"{c+' rdem':>14} {c+' LIG':>14} {'rel':>8}" + extra(c) for c in cols))
for s in steps:
    out = []
    for c in cols:
        a, b = r[s][c], l[s][c]
        cell = f"{a:14.6g} {b:14.6g} {rel(a, b):8.2%}"
        if base is not None:
            cell += f" {rel(base[s][c], b):8.2%}"
        out.append(cell)
    print(f"{s:>10} " + " ".join(out))
EOF
