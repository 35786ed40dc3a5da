# fairshape as a package: `cmake --install` into a scratch prefix, then a
# consumer project built only from that tree (find_package(fairshape 0.1 COMPONENTS subdivision
# design), fairshape::design) runs the detail-preserving nose pull and must give the command
# line's result; a project with fairshape as a subdirectory links fairshape::mesh. Set by
# tests/CMakeLists.txt: BUILD_DIR (the configured build), SOURCE_DIR.
source "$(dirname "$0")/lib.sh"
S="$SCRATCH"
PREFIX="$S/prefix"
cmake --install "$BUILD_DIR" --prefix "$PREFIX" > "$S/install.txt" || fail "cmake --install"
[ -x "$PREFIX/bin/fairshape" ] || fail "the CLI was not installed"
[ -f "$PREFIX/include/fairshape/subdivision/multires_surface.h" ] || fail "headers are not under include/fairshape/"
[ ! -e "$PREFIX/include/core" ] || fail "a bare include/core was installed"
for f in fairshapeConfig.cmake fairshapeConfigVersion.cmake fairshapeTargets.cmake; do
  [ -f "$PREFIX/lib/cmake/fairshape/$f" ] || fail "lib/cmake/fairshape/$f missing"
done
# No installed header names a fairshape header without the prefix.
if grep -rqE '#include "(core|io|mesh|subdivision|design|energy|solver)/' "$PREFIX/include/fairshape"; then
  fail "an installed header includes a bare module path"
fi

# The consumer, configured against the prefix alone.
cmake -S "$SOURCE_DIR/tests/package/consumer" -B "$S/consumer" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$PREFIX" > "$S/consumer_cmake.txt" 2>&1 || { cat "$S/consumer_cmake.txt" >&2; fail "consumer: configure"; }
cmake --build "$S/consumer" -j 2 > "$S/consumer_build.txt" 2>&1 || { tail -30 "$S/consumer_build.txt" >&2; fail "consumer: build"; }
"$S/consumer/nose_pull" data/cow.off "$S/consumer.obj" > /dev/null || fail "consumer: run"
# A version the package does not offer is refused by find_package.
sed 's/fairshape 0.1 REQUIRED/fairshape 7.0 REQUIRED/' "$SOURCE_DIR/tests/package/consumer/CMakeLists.txt" > "$S/CMakeLists.txt"
mkdir -p "$S/wrong_version" && cp "$S/CMakeLists.txt" "$SOURCE_DIR/tests/package/consumer/nose_pull.cpp" "$S/wrong_version/"
if cmake -S "$S/wrong_version" -B "$S/wrong_version/build" -DCMAKE_PREFIX_PATH="$PREFIX" > "$S/wrong.txt" 2>&1; then
  fail "find_package(fairshape 7.0) was satisfied by 0.x"
fi
grep -q "version" "$S/wrong.txt" || { cat "$S/wrong.txt" >&2; fail "the refusal does not name the version"; }

# The same edit through the installed command line.
"$PREFIX/bin/fairshape" run configs/smoke/cow_nose_pull.yaml --out "$S/cli" \
  --set input.representation=catmull-clark --set input.levels=2 \
  --set 'energy=[{type: detail_preserving, alpha: 0.1, beta: 1.0}]' \
  --set 'problem={constraint_mode: kkt}' > /dev/null 2>&1 || fail "the installed CLI's run failed"
$PY - "$S" <<'PYEOF'
import csv, glob, sys
d = sys.argv[1]
def vertices(path):
    return [tuple(map(float, l.split()[1:4])) for l in open(path) if l.startswith("v ")]
row = list(csv.DictReader(open(f"{d}/cli/runs.csv")))[0]
assert row["termination"] == "converged", row
finals = glob.glob(f"{d}/cli/final.obj") + glob.glob(f"{d}/cli/final/*.obj")
assert len(finals) == 1, finals
cli, lib = vertices(finals[0]), vertices(f"{d}/consumer.obj")
assert len(cli) == len(lib) and len(lib) > 10000, (len(cli), len(lib))
worst = max(abs(a - b) for p, q in zip(cli, lib) for a, b in zip(p, q))
assert worst < 1e-12, f"library and command line differ by {worst}"
PYEOF

# The demo itself (its CI size): the installed CLI's detail-preserving run and the library's.
"$S/consumer/demo_edit" data/cow.off 200 2 "$S/demo_lib.obj" > /dev/null 2>&1 || fail "consumer: demo_edit"
"$PREFIX/bin/fairshape" run configs/demo.yaml --smoke --out "$S/demo" > /dev/null 2>&1 || fail "the installed CLI's demo failed"
$PY - "$S" <<'PYEOF'
import csv, sys
d = sys.argv[1]
def vertices(path):
    return [tuple(map(float, l.split()[1:4])) for l in open(path) if l.startswith("v ")]
row = [r for r in csv.DictReader(open(f"{d}/demo/runs.csv")) if "detail_preserving" in r["param.energy"]][0]
assert row["termination"] == "converged", row
cli, lib = vertices(f"{d}/demo/final/{row['run_id']}.obj"), vertices(f"{d}/demo_lib.obj")
assert len(cli) == len(lib) and len(lib) > 1000, (len(cli), len(lib))
worst = max(abs(a - b) for p, q in zip(cli, lib) for a, b in zip(p, q))
assert worst < 1e-12, f"the library's demo edit and the command line's differ by {worst}"
PYEOF

# fairshape inside another project's tree.
cmake -S "$SOURCE_DIR/tests/package/subproject" -B "$S/subproject" -DCMAKE_BUILD_TYPE=Release \
  -DFAIRSHAPE_SOURCE="$SOURCE_DIR" > "$S/sub_cmake.txt" 2>&1 || { tail -30 "$S/sub_cmake.txt" >&2; fail "subproject: configure"; }
cmake --build "$S/subproject" -j 2 --target mesh_info > "$S/sub_build.txt" 2>&1 || { tail -30 "$S/sub_build.txt" >&2; fail "subproject: build"; }
"$S/subproject/mesh_info" > /dev/null || fail "subproject: run"
echo "package_consumer: ok"
