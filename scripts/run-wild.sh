#!/usr/bin/env bash
# Runs every case of ../shared/wild (MANIFEST.tsv) with rdem for a wall-clock budget and
# prints, per case, whether it ran to its end, was still running without error when the
# budget ran out, or stopped with an error (and the first line of the error). Not part of
# CI: real cases run for hours.
#
# Usage: scripts/run-wild.sh [BUDGET_SECONDS=60] [RDEM=target/release/rdem] [CASE-PATTERN]
# Each case runs in a scratch copy of its folder (nothing is written beside the scripts).
set -uo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
budget="${1:-60}"
rdem="$(realpath "${2:-$here/target/release/rdem}")"
pattern="${3:-}"
wild="$(realpath "$here/../shared/wild")"
[ -x "$rdem" ] || { echo "no rdem binary at $rdem (cargo build --release -p rdem-cli)"; exit 2; }
[ -f "$wild/MANIFEST.tsv" ] || { echo "no $wild/MANIFEST.tsv"; exit 2; }
scratch="$(mktemp -d /tmp/rdem-wild.XXXXXX)"
trap 'rm -rf "$scratch"' EXIT
printf '%-42s %-10s %s\n' case result detail
tail -n +2 "$wild/MANIFEST.tsv" | while IFS=$'\t' read -r case main _rest; do
  [ -n "$pattern" ] && [[ "$case" != *$pattern* ]] && continue
  top="${case%%/*}"
  rm -rf "${scratch:?}/$top"
  cp -r "$wild/$top" "$scratch/$top"
  cd "$scratch/$case" || continue
  start=$(date +%s)
  timeout --signal=INT --kill-after=10 "$budget" "$rdem" -in "$main" -log none \
    >stdout.txt 2>stderr.txt </dev/null
  status=$?
  took=$(( $(date +%s) - start ))
  if [ $status -eq 0 ]; then
    steps=$(grep -c '^Loop time' stdout.txt)
    printf '%-42s %-10s %s\n' "$case" ran "to its end in ${took}s ($steps runs)"
  elif [ $status -eq 124 ] || [ $status -eq 130 ] || [ $status -eq 137 ]; then
    last=$(grep -E '^ +[0-9]+ ' stdout.txt | tail -1 | awk '{print $1}')
    printf '%-42s %-10s %s\n' "$case" running "no error in ${budget}s (last thermo step ${last:-none})"
  else
    err=$(grep -m1 -E '×|ERROR|error' stderr.txt stdout.txt | sed 's/^[^:]*://' | head -c 110)
    where=$(grep -m1 -oE '\[[^]]+:[0-9]+:[0-9]+\]' stderr.txt)
    printf '%-42s %-10s %s\n' "$case" stopped "$where $err"
  fi
  cd "$scratch" || exit 2
done
