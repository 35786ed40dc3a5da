source "$(dirname "$0")/lib.sh"
"$FS" info data/knot.off > "$SCRATCH/info.txt"
grep -q "genus                1" "$SCRATCH/info.txt" || fail "knot genus"
grep -q "vertices             2080" "$SCRATCH/info.txt" || fail "knot vertices"
grep -q "3-gons: 4160" "$SCRATCH/info.txt" || fail "polygon histogram"
"$FS" info data/mushroom.off | grep -q "boundary loops       1" || fail "mushroom boundary"

# OFF -> binary PLY -> OBJ -> VTP -> OFF keeps the mesh exactly (info output identical).
"$FS" convert data/double-torus-example.off "$SCRATCH/a.ply" --binary
"$FS" convert "$SCRATCH/a.ply" "$SCRATCH/b.obj"
"$FS" convert "$SCRATCH/b.obj" "$SCRATCH/c.vtp"
"$FS" convert "$SCRATCH/c.vtp" "$SCRATCH/d.off"
"$FS" info data/double-torus-example.off | tail -n +2 > "$SCRATCH/i0.txt"
"$FS" info "$SCRATCH/d.off" | tail -n +2 > "$SCRATCH/i1.txt"
diff "$SCRATCH/i0.txt" "$SCRATCH/i1.txt" || fail "round trip changed the mesh"
"$FS" info --help | grep -q "mesh file" || fail "help"
# Every registered component documents itself (factories run on empty blocks).
"$FS" list > "$SCRATCH/list.txt" || fail "list failed"
for name in detail_preserving normal rigid curve gauss_seidel energy_tolerance boundary_loop_near snap_ratio; do
  grep -q "$name" "$SCRATCH/list.txt" || fail "list lacks $name"
done
echo "info_convert: ok"
