#!/usr/bin/env bash
# Re-runs every probe in this directory with the real LIGGGHTS 3.8 and stores the
# full screen output next to it as <probe>.out (see ../README.md, "Observed
# behaviour"). Probes are either self-contained scripts (<probe>.in, which use
# common.in) or generators (<probe>.sh) that derive a variant of an installed
# tutorial at run time. Each probe runs in a temp dir (some write post/).
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
for f in "$HERE"/[a-e][0-9_]*.in "$HERE"/[a-e][0-9_]*.sh; do
  p="$(basename "$f")"; p="${p%.*}"
  tmp="$(mktemp -d)"
  cp "$HERE"/*.in "$HERE"/*.sh "$tmp/"
  mkdir -p "$tmp/post"
  if [[ "$f" == *.sh ]]; then cmd=(bash "$p.sh"); else cmd=(liggghts -in "$p.in" -log none -nocite); fi
  if (cd "$tmp" && "${cmd[@]}" > "$HERE/$p.out" 2>&1); then
    echo "$p: ok"
  else
    echo "$p: FAILED (see $p.out)"
  fi
  rm -rf "$tmp"
done
