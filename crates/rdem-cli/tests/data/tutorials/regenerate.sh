#!/usr/bin/env bash
# Regenerates the LIGGGHTS 3.8 reference data in this directory for the six
# mesh-free tutorial cases (see README.md).
#
#   usage: bash regenerate.sh            # all cases, original + 3 extra seeds
#          JOBS=1 bash regenerate.sh     # serial
#
# Needs the real LIGGGHTS 3.8 (`bash /work/shared/reference/setup-liggghts.sh`
# or `apt-get install liggghts liggghts-doc`). Nothing of LIGGGHTS is copied
# here: the tutorial scripts are run unmodified from the liggghts-doc package,
# followed by `include stats.in`. For the scatter runs the ONLY change is the
# `seed` value of the `insert/pack` fix.
#
# Writes (next to this script):
#   reference.txt   case atoms mean_z max_z mean_r   (original seeds)
#   scatter.txt     min/max/mean/stddev of mean_z over 4 seeds, plus raw runs
#   insertions.txt  every "INFO: Particle insertion ... inserted N" event
#   timings.txt     LIGGGHTS "Loop time of" figures per case (original seeds)
#   <case>.log      full screen output of the original-seed run
set -euo pipefail

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
TUT="${TUT:-/usr/share/doc/liggghts/examples/LIGGGHTS/Tutorials_public}"
JOBS="${JOBS:-2}"
LIGGGHTS="${LIGGGHTS:-liggghts}"
# Extra insert/pack seeds (primes > 10000, as LIGGGHTS requires; none of them
# is used by the tutorials themselves).
EXTRA_SEEDS="32452909 32452919 32452997"

# case-name  directory  input-file
CASES="newModels:contactModels:in.newModels
noCohesion:cohesion:in.noCohesion
cohesion:cohesion:in.cohesion
noHysteresis:hysteresis:in.noHysteresis
hysteresis:hysteresis:in.hysteresis
packing:packing:in.packing"

# ---------------------------------------------------------------------------
# run_one CASE DIR FILE SEED OUTFILE
#   SEED = "orig" runs the tutorial unmodified.
run_one() {
  local name="$1" dir="$2" file="$3" seed="$4" out="$5"
  local tmp
  tmp="$(mktemp -d "${TMPDIR:-/tmp}/rdem-ref-${name}-XXXXXX")"
  cp -r "$TUT/$dir/." "$tmp/"
  mkdir -p "$tmp/post"
  cp "$HERE/stats.in" "$tmp/stats.in"
  local input="$file"
  if [ "$seed" != "orig" ]; then
    # Only change: the number after `seed` on the insert/pack line.
    input="$file.seed$seed"
    sed -E "/insert\/pack/ s/(seed[[:space:]]+)[0-9]+/\1$seed/" "$tmp/$file" > "$tmp/$input"
    if diff -q "$tmp/$file" "$tmp/$input" >/dev/null; then
      echo "seed substitution failed for $name" >&2; exit 1
    fi
  fi
  printf 'include %s\ninclude stats.in\n' "$input" > "$tmp/wrapper.in"
  (cd "$tmp" && "$LIGGGHTS" -in wrapper.in -log none > "$out" 2>&1) || {
    echo "LIGGGHTS failed for $name seed $seed (see $out)" >&2; rm -rf "$tmp"; exit 1; }
  rm -rf "$tmp"
}

# last thermo row printed by stats.in: step atoms mean_z max_z mean_r
stats_of() {
  awk '/^ *Step +Atoms +rdemZave +rdemZmax +rdemRave *$/ {getline; row=$0} END {print row}' "$1" |
    awk '{print $2, $3, $4, $5}'
}

if [ "${1:-}" = "--one" ]; then   # internal: used through xargs below
  shift; run_one "$@"; exit 0
fi

command -v "$LIGGGHTS" >/dev/null || { echo "liggghts not found" >&2; exit 1; }
WORK="$(mktemp -d "${TMPDIR:-/tmp}/rdem-ref-XXXXXX")"
trap 'rm -rf "$WORK"' EXIT

# Build the job list: one line per run.
: > "$WORK/jobs"
while IFS=: read -r name dir file; do
  for seed in orig $EXTRA_SEEDS; do
    echo "$name $dir $file $seed $WORK/$name.$seed.log" >> "$WORK/jobs"
  done
done <<< "$CASES"

start=$(date +%s)
xargs -P "$JOBS" -L 1 bash "$HERE/regenerate.sh" --one < "$WORK/jobs"
end=$(date +%s)

VERSION_LINE="$(head -n 1 "$WORK/newModels.orig.log")"
DATE="$(date -u '+%Y-%m-%d %H:%M:%S UTC')"

# --- reference.txt ----------------------------------------------------------
{
  echo "# LIGGGHTS reference data for rdem (mesh-free tutorial cases)"
  echo "# date: $DATE"
  echo "# version: $VERSION_LINE"
  echo "# command (in a temp copy of the tutorial directory): $LIGGGHTS -in wrapper.in -log none"
  echo "# wrapper.in = 'include in.<case>' + 'include stats.in' (tutorial unmodified, original seeds)"
  echo "# columns: case atoms mean_z max_z mean_r   (SI units, values at the end of the script)"
  while IFS=: read -r name dir file; do
    echo "$name $(stats_of "$WORK/$name.orig.log")"
  done <<< "$CASES"
} > "$HERE/reference.txt"

# --- insertions.txt ---------------------------------------------------------
{
  echo "# every insertion event reported by LIGGGHTS, from lines like"
  echo "#   INFO: Particle insertion ins: inserted 1800 particle templates (mass 2.945243e-01) at step 1"
  echo "# columns: case seed step inserted inserted_mass_kg"
  while IFS=: read -r name dir file; do
    for seed in orig $EXTRA_SEEDS; do
      grep -E '^INFO: Particle insertion .*: inserted [0-9]+ particle templates' "$WORK/$name.$seed.log" |
        sed -E 's/.*inserted ([0-9]+) particle templates \(mass ([^)]*)\) at step ([0-9]+).*/\3 \1 \2/' |
        awk -v c="$name" -v s="$seed" '{print c, s, $1, $2, $3}'
    done
  done <<< "$CASES"
} > "$HERE/insertions.txt"

# --- scatter.txt ------------------------------------------------------------
{
  echo "# scatter of mean_z over 4 runs per case: the original insert/pack seed + $EXTRA_SEEDS"
  echo "# (the only change between runs is the seed value of the insert/pack fix)"
  echo "# date: $DATE; version: $VERSION_LINE"
  echo "# stddev is the sample standard deviation (n-1); rel_stddev = stddev/mean"
  echo "# columns: case n min max mean stddev rel_stddev"
  while IFS=: read -r name dir file; do
    for seed in orig $EXTRA_SEEDS; do
      stats_of "$WORK/$name.$seed.log" | awk '{print $2}'
    done | awk -v c="$name" '{v[NR]=$1; s+=$1; if(NR==1||$1<mn)mn=$1; if(NR==1||$1>mx)mx=$1}
      END {m=s/NR; for(i=1;i<=NR;i++) q+=(v[i]-m)^2; sd=(NR>1)?sqrt(q/(NR-1)):0;
           printf "%s %d %.9g %.9g %.9g %.4g %.4g\n", c, NR, mn, mx, m, sd, sd/m}'
  done <<< "$CASES"
  echo "#"
  echo "# raw runs; columns: # case seed atoms mean_z max_z mean_r"
  while IFS=: read -r name dir file; do
    for seed in orig $EXTRA_SEEDS; do
      echo "# $name $seed $(stats_of "$WORK/$name.$seed.log")"
    done
  done <<< "$CASES"
} > "$HERE/scatter.txt"

# --- timings.txt ------------------------------------------------------------
{
  echo "# LIGGGHTS 'Loop time of' figures (seconds, 1 MPI proc, 2 runs in parallel on a 2-core machine)"
  echo "# columns: case total_loop_time per-run loop times..."
  while IFS=: read -r name dir file; do
    grep -E '^Loop time of' "$WORK/$name.orig.log" |
      awk -v c="$name" '{t[NR]=$4; s+=$4} END {printf "%s %.4g", c, s; for(i=1;i<=NR;i++) printf " %s", t[i]; print ""}'
  done <<< "$CASES"
  echo "# wall time of the whole regeneration ($(wc -l < "$WORK/jobs") runs, $JOBS in parallel): $((end-start)) s"
} > "$HERE/timings.txt"

# --- full logs of the original-seed runs ------------------------------------
while IFS=: read -r name dir file; do
  log="$WORK/$name.orig.log"
  if [ "$(wc -c < "$log")" -gt 204800 ]; then
    # trim the middle of the output, keep first/last 1500 lines
    { head -n 1500 "$log"; echo "... [trimmed by regenerate.sh] ..."; tail -n 1500 "$log"; } > "$HERE/$name.log"
  else
    cp "$log" "$HERE/$name.log"
  fi
done <<< "$CASES"

cat "$HERE/reference.txt"
cat "$HERE/scatter.txt"
cat "$HERE/timings.txt"
