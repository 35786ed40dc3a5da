# Hostile input: every file, parameter and mesh either works or is refused up front.
# One line per input: the exit status expected and a fragment of the message. Every command
# runs under a time limit and a 4 GB address-space limit, so a hang or a blow-up fails here
# rather than the machine; exit statuses above 128 (a signal) always fail, and so does a
# process whose resident set exceeded 2 GiB.
source "$(dirname "$0")/lib.sh"
H="$SCRATCH/in"
mkdir -p "$H"
CASES=0
SMOKE=configs/smoke/cow_nose_pull.yaml

# The largest resident set of any process a command ran (workers included), in KiB, and its
# exit status; the command runs under the time and address-space limits.
peak_rss_run() {
  $PY - "$@" <<'PYEOF'
import resource, subprocess, sys
rc = subprocess.call(["bash", "-c", 'ulimit -v 4000000; exec timeout 60 "$@"', "limited"] + sys.argv[1:],
                     stdout=subprocess.DEVNULL)
print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss, rc)
PYEOF
}

# hostile CODE PATTERN -- command...
hostile() {
  local code="$1" pattern="$2"; shift 3
  local err="$SCRATCH/stderr.txt" rc=0 rss=0
  read -r rss rc < <(peak_rss_run "$@" 2>"$err")
  CASES=$((CASES + 1))
  [ "$rc" -ge 0 ] && [ "$rc" -lt 124 ] || { cat "$err" >&2; fail "case $CASES: exit $rc (signal, timeout or blow-up): $*"; }
  [ "$rss" -le 2097152 ] || fail "case $CASES: a process held $((rss / 1024)) MiB, above 2 GiB: $*"
  [ "$rc" -eq "$code" ] || { cat "$err" >&2; fail "case $CASES: exit $rc, expected $code: $*"; }
  grep -q -- "$pattern" "$err" || { cat "$err" >&2; fail "case $CASES: stderr lacks '$pattern': $*"; }
  ! grep -qi "internal error" "$err" || { cat "$err" >&2; fail "case $CASES: an internal error: $*"; }
}

# --- mesh files ---------------------------------------------------------------------------
section_meshes() {
# A fan of n triangles around vertex 1 (`closed`: around the whole circle, a cone).
fan() {
  $PY - "$1" "$2" "$3" <<'PYEOF'
import math, sys
path, n, closed = sys.argv[1], int(sys.argv[2]), sys.argv[3] == "closed"
with open(path, "w") as f:
    f.write(f"v 0 0 {1 if closed else 0}\n")
    for k in range(n):
        a = 2 * math.pi * k / n
        f.write(f"v {math.cos(a):.9f} {math.sin(a):.9f} 0\n")
    for k in range(n if closed else n - 1):
        f.write(f"f 1 {k + 2} {(k + 1) % n + 2}\n")
PYEOF
}
# A fan around one vertex of valence 50,000: refused by name, not a crash after 2.3 s.
fan "$H/fan.obj" 50000 open
hostile 2 "vertex 0 has valence 50000" -- "$FS" energy "$H/fan.obj" --out "$H/fan.mtx"
[ ! -e "$H/fan.mtx" ] || fail "a refused energy wrote its matrix"
# Just over the documented limit and at it: a closed fan (a cone) of valence 2049 is refused,
# one of 2048 is assembled.
fan "$H/cone2048.obj" 2048 closed
fan "$H/cone2049.obj" 2049 closed
hostile 2 "has valence 2049" -- "$FS" energy "$H/cone2049.obj" --out "$H/cone.mtx"
(ulimit -v 4000000; timeout 60 "$FS" energy "$H/cone2048.obj" --out "$H/cone.mtx") > /dev/null 2>&1 ||
  fail "a cone of valence 2048, at the limit, was not assembled"
CASES=$((CASES + 1))
# The umbrella thin plate couples the ring too: a run on the fan is refused by validation,
# before anything runs, as is the sweep point that uses the fan (and only that point is named).
hostile 2 "accepts valence up to 2048" -- "$FS" run $SMOKE --out "$H/fan_run" --set "input.mesh=$H/fan.obj" \
  --set 'energy=[{type: umbrella_thin_plate}]' \
  --set 'constraints=[{type: fixed, vertices: [1, 2, 3]}, {type: position, vertices: [0], offset: [0, 0, 1]}]'
[ ! -e "$H/fan_run/runs.csv" ] || fail "the fan's run was started"
hostile 2 "accepts valence up to 2048.* (point 1)" -- "$FS" run $SMOKE --out "$H/fan_sweep" \
  --set "sweep.input.mesh=[data/cow.off, $H/fan.obj]" --set 'energy=[{type: umbrella_thin_plate}]' \
  --set 'constraints=[{type: fixed, vertices: [1, 2, 3]}, {type: position, vertices: [0], offset: [0, 0, 1]}]'
[ ! -e "$H/fan_sweep/runs.csv" ] || fail "a sweep with an invalid point started its valid one"
# Binary PLY whose face-list count is a float NaN, or a non-integral float.
$PY - "$H" <<'PYEOF'
import struct, sys
d = sys.argv[1]
def ply(name, count, index):
    head = (b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
            b"property float z\nelement face 1\nproperty list float float vertex_indices\nend_header\n")
    body = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0) + struct.pack("<f", count) + struct.pack("<3f", 0, 1, index)
    open(f"{d}/{name}", "wb").write(head + body)
ply("nan_count.ply", float("nan"), 2)
ply("fractional_count.ply", 3.7, 2)
ply("fractional_index.ply", 3, 1.9)
open(f"{d}/comment_end_header.ply", "w").write(
    "ply\nformat ascii 1.0\ncomment written before end_header by a tool\nelement vertex 3\nproperty float x\n"
    "property float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
open(f"{d}/bom.obj", "wb").write(b"\xef\xbb\xbfv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
open(f"{d}/bom.off", "wb").write(b"\xef\xbb\xbfOFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
open(f"{d}/empty.obj", "w").write("")
open(f"{d}/junk.obj", "w").write("this is not a mesh\nat all\n")
PYEOF
hostile 2 "list length nan is not a whole number" -- "$FS" info "$H/nan_count.ply"
hostile 2 "list length 3.7 is not a whole number" -- "$FS" info "$H/fractional_count.ply"
hostile 2 "vertex index 1.9 is not a whole number" -- "$FS" info "$H/fractional_index.ply"
"$FS" info "$H/comment_end_header.ply" > /dev/null 2>&1 || fail "a PLY comment naming end_header broke a valid file"
"$FS" info "$H/bom.obj" | grep -q "vertices *3" || fail "a UTF-8 BOM lost the OBJ's first vertex"
"$FS" info "$H/bom.off" > /dev/null 2>&1 || fail "a UTF-8 BOM broke an OFF file"
# Devices, FIFOs and directories are not meshes: refused at once (no 4 GB read, no hang).
ln -sf /dev/zero "$H/zero.off"
ln -sf /dev/urandom "$H/random.ply"
mkfifo "$H/fifo.obj"
mkdir -p "$H/folder.obj"
hostile 2 "not a regular file" -- "$FS" info "$H/zero.off"
hostile 2 "not a regular file" -- "$FS" info "$H/random.ply"
hostile 2 "not a regular file" -- "$FS" info "$H/fifo.obj"
hostile 2 "is a directory" -- "$FS" info "$H/folder.obj"
hostile 2 "is a directory" -- "$FS" convert "$H/folder.obj" "$H/out.off"
hostile 2 "no vertices" -- "$FS" convert "$H/empty.obj" "$H/out.off"
hostile 2 "no vertices" -- "$FS" convert "$H/junk.obj" "$H/out.off"
[ ! -e "$H/out.off" ] || fail "a refused conversion wrote its output"
hostile 2 "valid: .obj, .off, .ply, .vtp" -- "$FS" convert data/cow.off "$H/cow.stl"
hostile 2 "valid: .obj, .off, .ply, .vtp" -- "$FS" info "$H/cow.stl"
hostile 2 "only PLY output has a binary form" -- "$FS" convert data/cow.off "$H/cow.obj" --binary
hostile 2 "cannot open" -- "$FS" info "$H/missing.off"
"$FS" convert data/cow.off "$H/cow_copy.vtp" 2>/dev/null || fail "cow.off to .vtp"
# The malformed-file corpus (tests/data/malformed, also the fuzzers' seeds): every file is
# refused with its own name in the message.
for f in tests/data/malformed/*.obj tests/data/malformed/*.off tests/data/malformed/*.ply tests/data/malformed/*.stl; do
  hostile 2 "$(basename "$f")" -- "$FS" info "$f"
done

# VTK polydata: counts checked before VTK allocates, ids checked as 64-bit.
sed 's/NumberOfPoints="2904"/NumberOfPoints="1000000000000"/' "$H/cow_copy.vtp" > "$H/huge_count.vtp"
hostile 2 "is not a count up to" -- "$FS" info "$H/huge_count.vtp"
# The XML is parsed, not scanned: attribute values count whatever their quoting and spacing
# (single quotes, spaces around '='), components as much as points (NumberOfComponents, from a
# 600-byte file, hung info, convert and subdivide), inline compressed arrays as much as
# appended ones. Each is refused at once: hostile_quick adds a 2 s bound (a refusal is
# immediate; the margin is for a loaded machine) to hostile's memory bounds.
hostile_quick() {
  local t0 ms
  t0=$(date +%s%N)
  hostile "$@"
  ms=$((($(date +%s%N) - t0) / 1000000))
  [ "$ms" -lt 2000 ] || fail "case $CASES took $ms ms, not a prompt refusal: ${*:4}"
}
sed "s/NumberOfPoints=\"2904\"/NumberOfPoints='1000000000000'/" "$H/cow_copy.vtp" > "$H/single_quoted_count.vtp"
sed 's/NumberOfPoints="2904"/NumberOfPoints = "1000000000000"/' "$H/cow_copy.vtp" > "$H/spaced_count.vtp"
sed "s/NumberOfPoints=\"2904\"/NumberOfPoints\t=\t'1000000000000'/" "$H/cow_copy.vtp" > "$H/tab_spaced_count.vtp"
for f in single_quoted_count spaced_count tab_spaced_count; do
  hostile_quick 2 "$f.vtp:[0-9]*: Piece NumberOfPoints=\"1000000000000\" is not a count up to" -- "$FS" info "$H/$f.vtp"
done
components_vtp() {  # $1: the file, $2: the data array's NumberOfComponents attribute as written
  cat > "$1" <<VTP
<?xml version="1.0"?>
<VTKFile type="PolyData" version="0.1" byte_order="LittleEndian">
  <PolyData>
    <Piece NumberOfPoints="3" NumberOfPolys="1">
      <PointData><DataArray type="Float64" Name="weight" $2 format="ascii">0 0 0</DataArray></PointData>
      <Points><DataArray type="Float64" NumberOfComponents="3" format="ascii">0 0 0 1 0 0 0 1 0</DataArray></Points>
      <Polys>
        <DataArray type="Int64" Name="connectivity" format="ascii">0 1 2</DataArray>
        <DataArray type="Int64" Name="offsets" format="ascii">3</DataArray>
      </Polys>
    </Piece>
  </PolyData>
</VTKFile>
VTP
}
components_vtp "$H/huge_components.vtp" "NumberOfComponents='4000000000'"
components_vtp "$H/many_components.vtp" 'NumberOfComponents = "50000000"'
for cmd in info convert subdivide; do
  out=(); [ "$cmd" = info ] || out=("$H/components_out.obj")
  [ "$cmd" != subdivide ] || out+=(--scheme loop --levels 1)
  hostile_quick 2 "huge_components.vtp:5: DataArray NumberOfComponents=\"4000000000\" is not a count up to" -- "$FS" $cmd "$H/huge_components.vtp" "${out[@]}"
  hostile_quick 2 "many_components.vtp:5: <DataArray Name=\"weight\">: 50000000 components x 3 tuples is more than this .*-byte file can hold" -- \
    "$FS" $cmd "$H/many_components.vtp" "${out[@]}"
done
[ ! -e "$H/components_out.obj" ] || fail "a refused .vtp was converted"
# Inline (format="binary") compressed data whose header claims a 2^36-byte block.
$PY - "$H" <<'PYEOF'
import base64, struct, sys, zlib
points = struct.pack("<9d", 0, 0, 0, 1, 0, 0, 0, 1, 0)
z = zlib.compress(points)
header = struct.pack("<4Q", 1, 1 << 36, 1 << 36, len(z))
inline = (base64.b64encode(header) + base64.b64encode(z)).decode()
open(f"{sys.argv[1]}/inline_huge_block.vtp", "w").write(f"""<?xml version="1.0"?>
<VTKFile type="PolyData" version="0.1" byte_order="LittleEndian" header_type="UInt64" compressor="vtkZLibDataCompressor">
  <PolyData>
    <Piece NumberOfPoints="3" NumberOfPolys="1">
      <Points><DataArray type="Float64" NumberOfComponents="3" format="binary">{inline}</DataArray></Points>
      <Polys>
        <DataArray type="Int64" Name="connectivity" format="ascii">0 1 2</DataArray>
        <DataArray type="Int64" Name="offsets" format="ascii">3</DataArray>
      </Polys>
    </Piece>
  </PolyData>
</VTKFile>
""")
PYEOF
hostile_quick 2 "inline_huge_block.vtp:5: an inline array's header is inconsistent with the compressed data" -- "$FS" info "$H/inline_huge_block.vtp"
# The fuzzer's VTK corpus: each hostile file refused promptly, naming itself; the valid ones read.
for f in tests/fuzz/vtp/*.vtp; do
  case "$(basename "$f")" in
    valid_*) "$FS" info "$f" > /dev/null 2>&1 || fail "$f, a valid file of the fuzz corpus, was not read" ;;
    *) hostile_quick 2 "$(basename "$f")" -- "$FS" info "$f" ;;
  esac
done
cat > "$H/wrapped_id.vtp" <<'VTP'
<?xml version="1.0"?>
<VTKFile type="PolyData" version="0.1" byte_order="LittleEndian" header_type="UInt64">
  <PolyData>
    <Piece NumberOfPoints="3" NumberOfPolys="1">
      <Points><DataArray type="Float64" NumberOfComponents="3" format="ascii">0 0 0 1 0 0 0 1 0</DataArray></Points>
      <Polys>
        <DataArray type="Int64" Name="connectivity" format="ascii">0 1 4294967298</DataArray>
        <DataArray type="Int64" Name="offsets" format="ascii">3</DataArray>
      </Polys>
    </Piece>
  </PolyData>
</VTKFile>
VTP
hostile 2 "references point 4294967298" -- "$FS" info "$H/wrapped_id.vtp"
printf '<?xml version="1.0"?>\n<VTKFile type="PolyData"><PolyData><Piece NumberOfPoints="3"' > "$H/cut.vtp"
hostile 2 "cut.vtp" -- "$FS" info "$H/cut.vtp"
! grep -q "vtkXML\|ERROR: In" "$SCRATCH/stderr.txt" || fail "VTK's own log lines leaked onto stderr"
# A compressed base64 header claiming a 2.7 GB block in a 3 KB file (found by fuzz_read_vtp).
hostile 2 "appended array's header" -- "$FS" info tests/fuzz/vtp/regression_oom_block_header.vtp
# Big-endian appended data: read, and its headers checked in the file's byte order.
$PY - "$H" <<'PYEOF'
import struct, sys
def vtp(order, claim=None):
    fmt = ">" if order == "BigEndian" else "<"
    arrays = [struct.pack(fmt + "9d", 0, 0, 0, 1, 0, 0, 0, 1, 0), struct.pack(fmt + "3q", 0, 1, 2), struct.pack(fmt + "q", 3)]
    blob, offsets = b"", []
    for i, a in enumerate(arrays):
        offsets.append(len(blob))
        blob += struct.pack(fmt + "Q", claim if claim and i == 0 else len(a)) + a
    head = (f'<?xml version="1.0"?>\n<VTKFile type="PolyData" version="0.1" byte_order="{order}" header_type="UInt64">\n'
            f'<PolyData><Piece NumberOfPoints="3" NumberOfPolys="1">\n'
            f'<Points><DataArray type="Float64" NumberOfComponents="3" format="appended" offset="{offsets[0]}"/></Points>\n'
            f'<Polys><DataArray type="Int64" Name="connectivity" format="appended" offset="{offsets[1]}"/>\n'
            f'<DataArray type="Int64" Name="offsets" format="appended" offset="{offsets[2]}"/></Polys>\n'
            f'</Piece></PolyData>\n<AppendedData encoding="raw">\n_')
    return head.encode() + blob + b"\n</AppendedData>\n</VTKFile>\n"
open(f"{sys.argv[1]}/big_endian.vtp", "wb").write(vtp("BigEndian"))
open(f"{sys.argv[1]}/big_endian_claim.vtp", "wb").write(vtp("BigEndian", 1 << 40))
PYEOF
"$FS" info "$H/big_endian.vtp" 2>/dev/null | grep -q "faces *1" || fail "a valid big-endian .vtp was not read"
hostile 2 "claims more bytes than the file holds" -- "$FS" info "$H/big_endian_claim.vtp"
# Just over the size limits, as sparse files (nothing is read).
truncate -s 2147483649 "$H/over_limit.off"
hostile 2 "above the input limit of 2048 MiB" -- "$FS" info "$H/over_limit.off"
rm -f "$H/over_limit.off"
truncate -s 16777217 "$H/over_limit.yaml"
hostile 2 "above the input limit of 16 MiB" -- "$FS" run "$H/over_limit.yaml" --dry-run
rm -f "$H/over_limit.yaml"
ln -sf /dev/zero "$H/zero.vtp"
hostile 2 "not a regular file" -- "$FS" info "$H/zero.vtp"
# A full disk (a 10 KB file-size limit, SIGXFSZ ignored so writes fail with EFBIG): VTK's
# writers would report success; the output is refused and nothing truncated is left.
FULL_DISK=(bash -c 'ulimit -f 10; trap "" XFSZ; exec "$0" "$@"')
hostile 2 "could not write the file completely" -- "${FULL_DISK[@]}" "$FS" convert data/cow.off "$H/full.vtp"
[ ! -e "$H/full.vtp" ] || fail "a truncated .vtp was left in place"
hostile 2 "could not write" -- "${FULL_DISK[@]}" "$FS" subdivide data/cow.off "$H/full.vtm" --scheme catmull-clark --levels 2
[ ! -e "$H/full.vtm" ] || fail "a truncated .vtm was left in place"
# Inside a sweep the run's row says output_failed, and --resume runs it again.
rc=0
(ulimit -f 200; trap '' XFSZ; "$FS" run $SMOKE --out "$H/full_run" --set output.reference_solution=false) 2>/dev/null || rc=$?
CASES=$((CASES + 1))
[ "$rc" -eq 3 ] || fail "a sweep on a full disk: exit $rc, expected 3"
grep -q "output_failed" "$H/full_run/runs.csv" || fail "no output_failed row"
"$FS" run $SMOKE --out "$H/full_run" --set output.reference_solution=false --resume 2> "$SCRATCH/resume.txt" ||
  { cat "$SCRATCH/resume.txt" >&2; fail "the resume after the full disk did not finish"; }
grep -q "could not be written will run again" "$SCRATCH/resume.txt" || fail "the resume did not say it re-runs the run"
grep -q ",converged," "$H/full_run/runs.csv" || fail "the re-run is not recorded"
! grep -q "output_failed" "$H/full_run/runs.csv" || fail "the failed row stayed"

# A curve split into two `l` statements that share vertex 65 (as exporters write it) is one
# curve of 129 points, also with its second piece written backwards (the first piece alone was
# edited, the other 64 points dropped); two curves that do not meet are refused, naming the lines.
$PY - "$H" <<'PYEOF'
import sys
v = [l for l in open("data/curves/wave129.obj").read().splitlines() if l.startswith("v ")]
assert len(v) == 129
l = lambda ids: "l " + " ".join(map(str, ids))
def obj(name, *lines): open(f"{sys.argv[1]}/{name}.obj", "w").write("\n".join(v + list(lines)) + "\n")
obj("split", l(range(1, 66)), l(range(65, 130)))
obj("split_reversed", l(range(1, 66)), l(range(129, 64, -1)))
obj("two_curves", l(range(1, 65)), l(range(66, 130)))
PYEOF
for f in split split_reversed; do
  "$FS" run configs/sauvage/fig1.yaml --out "$H/$f" --set "input.curve=$H/$f.obj" --set 'sweep={}' 2>/dev/null ||
    fail "a curve in two 'l' statements ($f.obj) was not edited"
  CASES=$((CASES + 1))
  grep -q ",converged," "$H/$f/runs.csv" || fail "$f.obj: the edit did not converge"
  [ "$(grep -c '^v ' "$H/$f/final.obj")" -eq 129 ] || fail "$f.obj: the result is not the whole curve of 129 points"
done
hostile 2 "two_curves.obj:131: this polyline (vertices 66 to 129) does not continue the curve of line(s) 130, which ends at vertex 64" -- \
  "$FS" run configs/sauvage/fig1.yaml --dry-run --set "input.curve=$H/two_curves.obj"
# Results too large to stay finite are refused, naming where, and nothing is written (they were
# written as inf and nan, exit 0).
hostile 2 "energy: the Hessian has a non-finite entry" -- "$FS" energy data/cow.off --alpha 1e308 --beta 1e308 --out "$H/inf.mtx"
[ ! -e "$H/inf.mtx" ] || fail "a non-finite Hessian was written"
# A cube with every coordinate 1e308 or 1.5e308: the vertex rule's sums overflow.
$PY - "$H/huge_coordinates.obj" <<'PYEOF'
import itertools, sys
with open(sys.argv[1], "w") as f:
    for p in itertools.product((1.0e308, 1.5e308), repeat=3):
        f.write("v %r %r %r\n" % p)
    f.write("f 1 2 4 3\nf 5 7 8 6\nf 1 5 6 2\nf 3 4 8 7\nf 1 3 7 5\nf 2 6 8 4\n")
PYEOF
hostile 2 "subdivide: level [12] has non-finite positions (vertex [0-9]*): the input's coordinates are too large" -- \
  "$FS" subdivide "$H/huge_coordinates.obj" "$H/huge_subdivided.obj" --scheme catmull-clark --levels 2
hostile 2 "subdivide: level [12] has non-finite positions" -- \
  "$FS" subdivide "$H/huge_coordinates.obj" "$H/huge_subdivided.vtm" --scheme catmull-clark --levels 2
[ -z "$(ls "$H" | grep huge_subdivided)" ] || fail "a refused subdivision left files: $(ls "$H" | grep huge_subdivided)"
}

# --- configs ------------------------------------------------------------------------------
section_configs() {
cfg() { printf '%s\n' "$2" > "$H/$1.yaml"; echo "$H/$1.yaml"; }
hostile 2 "key 'name' repeats the key of line 1" -- "$FS" run "$(cfg dup_key "name: a
name: b")" --dry-run
hostile 2 "key 'type' repeats the key of line" -- "$FS" run "$(cfg dup_nested "defaults: [$PWD/$SMOKE]
solver: {type: sor, type: cholesky}")" --dry-run
hostile 2 "a map key must be a plain value" -- "$FS" run "$(cfg complex_key "? [a, b]
: 1")" --dry-run
hostile 2 "a \`defaults\` entry must be a file name" -- "$FS" run "$(cfg bad_defaults "defaults: [[a, b]]
name: x")" --dry-run
hostile 2 "include themselves" -- "$FS" run "$(cfg self_include "defaults: [self_include.yaml]
name: x")" --dry-run
# A second YAML document was ignored; a non-UTF-8 byte was an internal error (exit 1) after
# config.resolved.yaml and vtk/ were written. Both are refused, by line, before --out is made.
hostile 2 "two_documents.yaml:3: a second YAML document starts here" -- "$FS" run "$(cfg two_documents "defaults: [$PWD/$SMOKE]
name: first
---
name: second")" --out "$H/two_documents_out"
[ ! -e "$H/two_documents_out" ] || fail "a refused config made its output folder"
printf 'defaults: [%s]\ndescription: caf\xe9 au lait\n' "$PWD/$SMOKE" > "$H/latin1.yaml"
hostile 2 "latin1.yaml:2: byte 0xE9 at column 17 is not UTF-8" -- "$FS" run "$H/latin1.yaml" --out "$H/latin1_out"
[ ! -e "$H/latin1_out" ] || fail "a config refused for its encoding made its output folder"
hostile 2 "--set 'description':1: byte 0xE9" -- "$FS" run $SMOKE --set "description=caf$(printf '\xe9')" --out "$H/latin1_set"
[ ! -e "$H/latin1_set" ] || fail "a --set refused for its encoding made its output folder"
# A diamond of includes 12 deep, 4 wide: each file is loaded once (was exponential: a hang).
for d in $(seq 0 12); do
  if [ "$d" -eq 12 ]; then printf 'name: deep\n' > "$H/level$d.yaml"
  else n=$((d + 1)); printf 'defaults: [level%s.yaml, level%s.yaml, level%s.yaml, level%s.yaml]\n' $n $n $n $n > "$H/level$d.yaml"; fi
done
hostile 2 "is no run kind's" -- "$FS" run "$H/level0.yaml" --dry-run
# Text on which yaml-cpp's event parser reports documents without end (found by fuzz_config).
hostile 2 "" -- "$FS" run tests/fuzz/config/regression_endless_documents.yaml --dry-run
ln -sf /dev/zero "$H/zero.yaml"
hostile 2 "not a regular file" -- "$FS" run "$H/zero.yaml" --dry-run
mkfifo "$H/fifo.yaml"
hostile 2 "not a regular file" -- "$FS" run "$H/fifo.yaml" --dry-run
hostile 2 "config file not found" -- "$FS" run "$H/none.yaml"
# A malformed or non-manifold input mesh is found while validating, before anything runs.
hostile 2 "input.mesh: .*nonmanifold_edge.off" -- "$FS" run $SMOKE --set "input.mesh=$PWD/tests/data/malformed/nonmanifold_edge.off" --out "$H/bad_mesh"
[ ! -e "$H/bad_mesh/runs.csv" ] || fail "a malformed input mesh started runs"
ln -sf /dev/zero "$H/zero.off"
hostile 2 "input.mesh: .*not a regular file" -- "$FS" run configs/khodakovsky-schroder/fig11.yaml --set "input.mesh=$H/zero.off" --dry-run
hostile 2 "unknown key" -- "$FS" run $SMOKE --set colour=red --dry-run
hostile 2 "valid: cholesky" -- "$FS" run $SMOKE --set solver.type=lu --dry-run
# Non-finite or absurd parameters.
hostile 2 "expected finite numbers" -- "$FS" run $SMOKE --set 'constraints.1.nearest=[.nan, 0, 0]' --dry-run
hostile 2 "expected finite numbers" -- "$FS" run $SMOKE --set 'constraints.1.offset=[.inf, 0, 0]' --dry-run
hostile 2 "expected finite numbers" -- "$FS" run $SMOKE --set 'energy.1.weight=.nan' --dry-run
hostile 2 "out of range" -- "$FS" run $SMOKE --set 'energy.1.weight=-1' --dry-run
hostile 2 "out of range" -- "$FS" run $SMOKE --set solver.tolerance=-1 --dry-run
hostile 2 "out of range" -- "$FS" run $SMOKE --set repeat=0 --dry-run
hostile 2 "out of range" -- "$FS" run $SMOKE --set input.levels=40 --dry-run
hostile 2 "spans: 100000 x 100000 base spans" -- "$FS" run configs/welch-witkin/fig1.yaml \
  --set 'sheets.0.spans=[100000, 100000]' --dry-run
hostile 2 "not finite" -- "$FS" energy data/cow.off --alpha nan --out "$H/e.mtx"
hostile 2 "not finite" -- "$FS" energy data/cow.off --beta inf --out "$H/e.mtx"
hostile 2 "must be >= 0" -- "$FS" energy data/cow.off --alpha -1 --out "$H/e.mtx"
# An offset so large that the solve overflows: a failure row, never NaN marked converged.
rc=0
"$FS" run $SMOKE --out "$H/huge" --set 'constraints.1.offset=[1.0e308, 0, 0]' 2>/dev/null || rc=$?
CASES=$((CASES + 1))
[ "$rc" -eq 3 ] || fail "an overflowing offset: exit $rc, expected 3"
$PY - "$H/huge/runs.csv" <<'PYEOF'
import csv, sys
r = list(csv.DictReader(open(sys.argv[1])))[0]
assert r["termination"] == "numerical_failure", r["termination"]
assert "non-finite" in r["message"], r["message"]
PYEOF
}

# --- constraints and curves placed on the input's geometry, before anything runs ----------
section_placement() {
FIX='{type: fixed, region: {axis: x, from: 0.0, to: 0.3}}'
hostile 2 "vertex 5 of level 0 has incompatible targets" -- "$FS" run $SMOKE --out "$H/c1" \
  --set 'constraints=[{type: fixed, vertices: [5]}, {type: position, vertices: [5], offset: [1, 0, 0]}]'
hostile 2 "has incompatible normals" -- "$FS" run $SMOKE --dry-run --set "constraints=[$FIX, \
  {type: normal, vertices: [1500], normal: [0, 0, 1]}, {type: normal, vertices: [1500], normal: [0, 0, -1]}]"
hostile 2 "vertex 999999 does not exist" -- "$FS" run $SMOKE --dry-run \
  --set "constraints=[$FIX, {type: position, vertices: [999999], offset: [0, 0, 1]}]"
hostile 2 "level 3 is not in the hierarchy (levels 0..1)" -- "$FS" run $SMOKE --dry-run \
  --set input.representation=catmull-clark --set input.levels=1 \
  --set "constraints=[$FIX, {type: position, level: 3, vertices: [2], offset: [0, 0, 1]}]"
hostile 2 "constraints\[0\]: selects no vertex" -- "$FS" run $SMOKE --dry-run \
  --set 'constraints.0.region={axis: x, from: 0.5001, to: 0.5002}'
hostile 2 "boundary_loop_near: the mesh has no boundary" -- "$FS" run $SMOKE --dry-run \
  --set 'constraints.0={type: fixed, boundary_loop_near: [0, 0, 0]}'
hostile 2 "the curve leaves the surface" -- "$FS" run $SMOKE --dry-run --set "constraints=[$FIX, \
  {type: curve, points: [[0.4, 0.0, 0.0], [3.0, 3.0, 3.0]], translation: [0, 0.1, 0]}]"
hostile 2 "no constraint: the deformation is undetermined" -- "$FS" run $SMOKE --dry-run --set 'constraints=[]'
hostile 2 "normal constraints fix no position" -- "$FS" run $SMOKE --dry-run \
  --set 'constraints=[{type: normal, vertices: [1500], normal: [0, 0, 1]}]'
# A feature curve drawn off the surface, and a curve edit pinning a point the curve lacks.
hostile 2 "features on .*ridge_a" -- "$FS" run configs/khodakovsky-schroder/fig11.yaml --dry-run \
  --set 'features.0.points=[[-0.8, -0.55, 3.0], [0.8, 0.7, 3.0]]'
hostile 2 "edits.0 on .*pin: point 100000 is not on the curve" -- "$FS" run configs/sauvage/fig1.yaml --dry-run \
  --set 'optimization.constraints=[{type: segment_lengths}, {type: pin, points: [100000]}]'
}

# --- command lines ------------------------------------------------------------------------
section_command_lines() {
hostile 2 "expected i/n" -- "$FS" run $SMOKE --shard 0/2x --out "$H/s"
hostile 2 "need 0 <= i < n" -- "$FS" run $SMOKE --shard 2/2 --out "$H/s"
hostile 2 "--filter" -- "$FS" run configs/examples/solvers_sweep.yaml --filter solver.type=none --out "$H/f"
touch "$H/a_file"
hostile 2 "not a folder" -- "$FS" run $SMOKE --out "$H/a_file"
hostile 2 "--jobs" -- "$FS" run $SMOKE --jobs 0 --out "$H/j"
hostile 2 "expected key.path=value" -- "$FS" run $SMOKE --set novalue
hostile 2 "must be a plain folder name" -- "$FS" run $SMOKE --set 'name=../escape' --dry-run
hostile 2 "must be a plain folder name" -- "$FS" run $SMOKE --set 'name=/abs/dir' --dry-run
# Nothing is written outside --out: a symbolic link inside it (the lock, final/, vtk/, a table)
# is refused by name before anything is written through it (the lock's target was truncated to
# a PID even by a refused run; results landed in a linked final/ or vtk/).
mkdir -p "$H/linked_lock" && printf 'keep\n' > "$H/lock_target" && ln -sfn "$H/lock_target" "$H/linked_lock/.lock"
hostile 2 "linked_lock/.lock: a symbolic link inside the output folder" -- "$FS" run $SMOKE --out "$H/linked_lock"
[ "$(cat "$H/lock_target")" = keep ] || fail "the target of a .lock link was written"
touch "$H/linked_lock/runs.csv"  # a folder with results: the run is refused for it later, the lock first
hostile 2 "linked_lock/.lock: a symbolic link" -- "$FS" run $SMOKE --out "$H/linked_lock"
[ "$(cat "$H/lock_target")" = keep ] || fail "a refused run wrote the target of a .lock link"
TWO_RUNS=(--set 'sweep={solver.tolerance: [1.0e-10, 1.0e-9]}')
for sub in final vtk runs.csv; do
  mkdir -p "$H/linked_$sub" "$H/outside_$sub"
  if [ "$sub" = runs.csv ]; then ln -sfn "$H/outside_$sub/runs.csv" "$H/linked_$sub/$sub"; else ln -sfn "$H/outside_$sub" "$H/linked_$sub/$sub"; fi
  hostile 2 "linked_$sub/$sub: a symbolic link inside the output folder" -- "$FS" run $SMOKE --out "$H/linked_$sub" "${TWO_RUNS[@]}"
  [ -z "$(ls -A "$H/outside_$sub")" ] || fail "a run wrote through a linked $sub: $(ls -A "$H/outside_$sub")"
done
}

# $2: the section this test runs (ctest runs the four side by side: cli.hostile_input.<section>).
declare -A PHRASE=([meshes]="file" [configs]="config" [placement]="placement" [command_lines]="command-line")
SECTION="${2:-}"
[ -n "${PHRASE[$SECTION]:-}" ] || fail "hostile_input.sh SECTION: one of ${!PHRASE[*]}"
"section_$SECTION"
[ "$CASES" -ge 10 ] || fail "only $CASES hostile cases in $SECTION"
# The README quotes each section's count: it must be the count the section ran.
grep -q "$CASES ${PHRASE[$SECTION]} inputs" README.md ||
  fail "README.md's count of hostile ${PHRASE[$SECTION]} inputs is not this section's $CASES: update it"
echo "hostile_input $SECTION: ok ($CASES cases)"
