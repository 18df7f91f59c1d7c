#!/usr/bin/env bash
# Parity table: runs every LIGGGHTS 3.8 tutorial script (Tutorials_public/*/in.*) with
# LIGGGHTS (`liggghts` on the PATH) and with rdem, each from its own scratch copy of the
# tutorial folder, and prints one markdown table: status, atom count and last thermo row
# of each program, the wall-time ratio and a verdict (`agree`, or why not). How agreement
# is judged is written in the table's header (see scripts/parity.py).
#
# Usage: scripts/parity.sh [--write] [RDEM=target/release/rdem] [BUDGET_SECONDS=600] [PATTERN]
#   RDEM            the rdem binary
#   BUDGET_SECONDS  wall-time limit of each single run (`timeout`)
#   PATTERN         extended regex on "folder/script" (e.g. packing, 'cohesion|conveyor')
#   --write         (or PARITY_WRITE=1) also writes the output to docs/parity.md
# Environment: TUTORIALS (default Debian's liggghts-doc folder), KEEP=1 keeps the scratch
# folder (its path is printed on stderr), SECOND_LOOK=0 skips the second look (step 5).
#
# Each script is run
#   1. by LIGGGHTS as it is;
#   2. by rdem as it is (with --threads 1), unless LIGGGHTS ran out of time;
#   3. by LIGGGHTS twice more with its insertion seeds replaced by other primes, if it
#      has any and run 1 ended well; without seeds, on 2 and 3 MPI processes instead:
#      the three LIGGGHTS runs give LIGGGHTS' own spread;
#   4. then by rdem with the same two seed sets, if its run 2 ended well: rdem's spread;
#   5. the second look: if the script has seeds, both ran it, and the verdict on these
#      runs is not `agree`, by both programs with six more seed sets (3 to 8), so that
#      LIGGGHTS' spread comes from nine runs (SECOND_LOOK=0 skips it).
# Every run starts from a fresh copy of the folder, runs in it with `-in SCRIPT -log none`
# and stdin from /dev/null, under `timeout BUDGET_SECONDS`. One run at a time. Nothing is
# written outside the scratch folder except docs/parity.md (with --write).
set -uo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"

# --- arguments -------------------------------------------------------------------------
write="${PARITY_WRITE:-0}"
args=()
for a in "$@"; do
  case "$a" in
    --write) write=1 ;;
    -h|--help) sed -n '2,27p' "$0"; exit 0 ;;
    *) args+=("$a") ;;
  esac
done
rdem="${args[0]:-$here/target/release/rdem}"
budget="${args[1]:-600}"
pattern="${args[2]:-}"
tutorials="${TUTORIALS:-/usr/share/doc/liggghts/examples/LIGGGHTS/Tutorials_public}"
[ -x "$rdem" ] || { echo "parity: no rdem binary at $rdem" >&2; exit 2; }
rdem="$(realpath "$rdem")"
command -v liggghts >/dev/null || { echo "parity: liggghts is not on the PATH" >&2; exit 2; }
[ -d "$tutorials" ] || { echo "parity: no tutorials at $tutorials" >&2; exit 2; }
[[ "$budget" =~ ^[0-9]+$ ]] || { echo "parity: BUDGET_SECONDS must be a whole number" >&2; exit 2; }

# What is compared, read before the runs (the tree may move on while they go).
commit="$(git -C "$here" rev-parse --short HEAD 2>/dev/null || echo unknown)"
load="$(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null)"
version="$({ liggghts -h </dev/null 2>/dev/null || true; } | grep -m1 'LIGGGHTS (Version')"
rdem_version="$("$rdem" -V 2>/dev/null | head -n 1)"

scratch="$(mktemp -d /tmp/rdem-parity.XXXXXX)"
if [ "${KEEP:-0}" = 1 ]; then
  echo "parity: scratch folder $scratch" >&2
else
  trap 'rm -rf "$scratch"' EXIT
fi

# --- one run ---------------------------------------------------------------------------
# run_one WHO RUN_DIR FOLDER SCRIPT [VARIANT]
# Copies tutorial FOLDER to RUN_DIR/work, replaces its seeds if VARIANT is a seed set
# (1 or 2), runs WHO (liggghts or rdem) on SCRIPT there (LIGGGHTS on N MPI processes if
# VARIANT is npN) and leaves RUN_DIR/{out,err,rc,secs}.
run_one() {
  local who="$1" dir="$2" folder="$3" script="$4" variant="${5:-}"
  mkdir -p "$dir"
  cp -r "$tutorials/$folder" "$dir/work"
  if [[ "$variant" =~ ^[0-9]+$ ]]; then
    python3 "$here/scripts/parity.py" reseed "$dir/work/$script" "$variant" >/dev/null
  fi
  # LIGGGHTS' screen output is line-buffered (stdbuf): an error that ends in MPI_Abort
  # would otherwise lose its ERROR line, still in the buffer of the file it goes to.
  local cmd=(stdbuf -oL liggghts -in "$script" -log none)
  if [[ "$variant" =~ ^np([0-9]+)$ ]]; then
    cmd=(mpirun --allow-run-as-root --oversubscribe -np "${BASH_REMATCH[1]}" "${cmd[@]}")
  fi
  [ "$who" = rdem ] && cmd=("$rdem" -in "$script" -log none --threads 1)
  local start end
  start=$(date +%s.%N)
  (cd "$dir/work" && timeout --kill-after=10 "$budget" "${cmd[@]}" \
    >"$dir/out" 2>"$dir/err" </dev/null)
  echo $? >"$dir/rc"
  end=$(date +%s.%N)
  python3 -c "print(f'{$end - $start:.3f}')" >"$dir/secs"
  echo "parity:   $who${variant:+ ($variant)}: exit $(cat "$dir/rc") in $(cat "$dir/secs") s" >&2
  rm -rf "$dir/work" # dumps and other files the script wrote are not needed
}

# --- every tutorial script -------------------------------------------------------------
n=0
while IFS= read -r path; do
  name="${path#"$tutorials"/}" # folder/in.script
  folder="${name%/*}"
  script="${name##*/}"
  [ -z "$pattern" ] || [[ "$name" =~ $pattern ]] || continue
  n=$((n + 1))
  d="$scratch/$(printf '%02d' "$n")"
  mkdir -p "$d"
  echo "$name" >"$d/name"
  echo "parity: $name" >&2
  run_one liggghts "$d/lig0" "$folder" "$script"
  if [ "$(cat "$d/lig0/rc")" = 124 ] || [ "$(cat "$d/lig0/rc")" = 137 ]; then
    continue # LIGGGHTS ran out of time: both are marked timeout, rdem is not run
  fi
  run_one rdem "$d/rdem" "$folder" "$script"
  # LIGGGHTS' spread: two more seeds, if the script has seeds and LIGGGHTS ran it.
  if [ "$(cat "$d/lig0/rc")" = 0 ] &&
    [ "$(python3 "$here/scripts/parity.py" reseed "$path" 1 --count)" -gt 0 ]; then
    run_one liggghts "$d/lig1" "$folder" "$script" 1
    run_one liggghts "$d/lig2" "$folder" "$script" 2
    if [ "$(cat "$d/rdem/rc")" = 0 ]; then
      run_one rdem "$d/rdem1" "$folder" "$script" 1
      run_one rdem "$d/rdem2" "$folder" "$script" 2
      # The second look (see parity.py's header text).
      if [ "${SECOND_LOOK:-1}" = 1 ] &&
        [ "$(python3 "$here/scripts/parity.py" verdict "$d" --budget "$budget")" != agree ]; then
        echo "parity:   second look" >&2
        for k in 3 4 5 6 7 8; do
          run_one liggghts "$d/lig$k" "$folder" "$script" "$k"
          run_one rdem "$d/rdem$k" "$folder" "$script" "$k"
        done
      fi
    fi
  elif [ "$(cat "$d/lig0/rc")" = 0 ]; then
    # No seeds: LIGGGHTS' spread from 2 and 3 MPI processes (only the order of its sums
    # differs, which a chaotic run grows into a different end state).
    run_one liggghts "$d/lig1" "$folder" "$script" np2
    run_one liggghts "$d/lig2" "$folder" "$script" np3
  fi
done < <(find "$tutorials" -mindepth 2 -maxdepth 2 -type f -name 'in.*' | LC_ALL=C sort)
[ "$n" -gt 0 ] || { echo "parity: no tutorial script matches '$pattern'" >&2; exit 2; }

# --- the table -------------------------------------------------------------------------
table() {
  python3 "$here/scripts/parity.py" table "$scratch" --budget "$budget" --commit "$commit" \
    --liggghts "$version" --rdem "$rdem ($rdem_version)" --nproc "$(nproc)" --load "$load" \
    --pattern "$pattern"
}
if [ "$write" = 1 ]; then
  mkdir -p "$here/docs"
  table | tee "$here/docs/parity.md"
else
  table
fi
