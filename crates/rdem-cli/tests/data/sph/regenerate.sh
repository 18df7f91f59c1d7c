#!/usr/bin/env bash
# Regenerates the LIGGGHTS 3.8 reference data of the SPH tests (tests/sph.rs):
#  - three.dump, kernel_*.dump, wall.dump, wall_region.dump, wall_sphere.dump,
#    wall_cylinder.dump, wall_xcylinder.dump, wall_sphere_out.dump, wall_block_out.dump,
#    wall_cylinder_out.dump, wall_plane.dump, wall_union.dump, wall_intersect.dump,
#    wall_cone.dump, wall_cone_out.dump, wall_union_out.dump, wall_move.dump,
#    wall_rotate.dump: the
#    small cases in.three, in.kernels, in.wall and in.wall_* of the same names
#    (dumps of every step, full precision);
#  - sph_2_short.log: the tutorial sph_2 (liggghts-doc, unmodified) up to and including
#    its `run 5000`, then `include stats.in`;
#  - sph_2_full.log: the whole tutorial sph_2, then `include stats.in` (about 45 s);
#    used by the report in docs, not by the tests;
#  - sph_1_2000.log: the tutorial sph_1 (3d) up to its `unfix wall`, with its `run 5000`
#    cut to `run 2000` (LIGGGHTS takes minutes for the whole).
# Nothing of LIGGGHTS is copied here: only its outputs.
#   usage: bash regenerate.sh [small|short|full|sph1 ...]   (default: small short sph1)
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
TUT="${TUT:-/usr/share/doc/liggghts/examples/LIGGGHTS/Tutorials_public}"
LIGGGHTS="${LIGGGHTS:-liggghts}"
WHAT=("$@")
[ ${#WHAT[@]} -gt 0 ] || WHAT=(small short sph1)
for w in "${WHAT[@]}"; do
  case "$w" in
    small)
      for c in three kernels wall wall_region wall_sphere wall_cylinder wall_xcylinder \
          wall_sphere_out wall_block_out wall_cylinder_out wall_plane wall_union wall_intersect \
          wall_cone wall_cone_out wall_union_out wall_move wall_rotate; do
        (cd "$HERE" && "$LIGGGHTS" -in "in.$c" -log none > /dev/null)
      done ;;
    short|full)
      tmp="$(mktemp -d "${TMPDIR:-/tmp}/rdem-sph-$w-XXXXXX")"
      cp -r "$TUT/sph_2/." "$tmp/"
      mkdir -p "$tmp/post"
      if [ "$w" = short ]; then
        # The tutorial up to its `unfix wall` (the runs of 1 and 5000 steps).
        sed '/^unfix/,$d' "$TUT/sph_2/in.sph_2" > "$tmp/in.part"
      else
        cp "$TUT/sph_2/in.sph_2" "$tmp/in.part"
      fi
      cp "$HERE/stats.in" "$tmp/stats.in"
      printf 'include in.part\ninclude stats.in\n' > "$tmp/wrapper.in"
      (cd "$tmp" && "$LIGGGHTS" -in wrapper.in -log none > "$HERE/sph_2_$w.log" 2>&1)
      rm -rf "$tmp" ;;
    sph1)
      tmp="$(mktemp -d "${TMPDIR:-/tmp}/rdem-sph-$w-XXXXXX")"
      cp -r "$TUT/sph_1/." "$tmp/"
      mkdir -p "$tmp/post"
      sed -e 's/^run  *5000$/run           2000/' -e '/^unfix/,$d' "$TUT/sph_1/in.sph_1" > "$tmp/in.part"
      (cd "$tmp" && "$LIGGGHTS" -in in.part -log none > "$HERE/sph_1_2000.log" 2>&1)
      rm -rf "$tmp" ;;
    *) echo "unknown: $w" >&2; exit 1 ;;
  esac
done
