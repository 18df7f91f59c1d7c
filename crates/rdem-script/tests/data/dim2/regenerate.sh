#!/bin/sh
# Records LIGGGHTS 3.8's output of in.2d (in.2d.liggghts.txt), which tests/dim2.rs
# hard-codes. Needs `liggghts` on PATH.
set -e
cd "$(dirname "$0")"
liggghts -in in.2d -log none > in.2d.liggghts.txt 2>&1 || true
