# fairshape without its optional dependencies: configured with
# FAIRSHAPE_WITH_VTK, _CGAL and _CERES off, the libraries that do not need them are generated and
# none of the subdivision, energy and design chain's compile or link commands names VTK, CGAL or
# Ceres; io (with its VTK stand-in) is built. Then with FAIRSHAPE_WITH_TBB off as well, inside a
# small project (tests/package/reference_only, add_subdirectory): TBB is not searched for, no
# command of subdivision, energy or design names it, both libraries build, a program gets the
# reference back end's answers and another the error for Backend::Optimized.
# Set by tests/CMakeLists.txt: SOURCE_DIR.
source "$(dirname "$0")/lib.sh"
S="$SCRATCH"
cmake -S "$SOURCE_DIR" -B "$S/build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DFAIRSHAPE_WITH_VTK=OFF \
  -DFAIRSHAPE_WITH_CGAL=OFF -DFAIRSHAPE_WITH_CERES=OFF -DFAIRSHAPE_WITH_PETSC=OFF > "$S/cmake.txt" 2>&1 || { tail -30 "$S/cmake.txt" >&2; fail "configure"; }
grep -q "tests, benchmarks and fuzzers need VTK, CGAL, Ceres and TBB: not built" "$S/cmake.txt" || fail "configure did not say what it leaves out"
targets=$(ninja -C "$S/build" -t targets all | cut -d: -f1)
for t in libfairshape_subdivision.a libfairshape_energy.a libfairshape_design.a libfairshape_curve_design.a; do
  echo "$targets" | grep -q "$t" || fail "$t is not built without the optional dependencies"
done
for t in libfairshape_render.a libfairshape_remesh.a libfairshape_feature.a bin/fairshape; do
  if echo "$targets" | grep -q "$t\$"; then fail "$t needs an optional dependency, yet it is generated"; fi
done
for t in fairshape_subdivision fairshape_energy fairshape_design fairshape_curve_design; do
  # (the FAIRSHAPE_WITH_*=0 definitions and the stand-in vtk_io_without_vtk.cpp aside)
  if ninja -C "$S/build" -t commands "$t" | sed 's/FAIRSHAPE_WITH_[A-Z]*=[01]//g; s/vtk_io_without_vtk//g' | grep -iqE "vtk|cgal|ceres"; then fail "$t's commands name VTK, CGAL or Ceres"; fi
done
cmake --build "$S/build" -j 2 --target fairshape_io > "$S/build.txt" 2>&1 || { tail -30 "$S/build.txt" >&2; fail "build io"; }

# Without TBB: the reference back ends alone.
T="$S/reference-only"
cmake -S "$SOURCE_DIR/tests/package/reference_only" -B "$T" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DFAIRSHAPE_SOURCE="$SOURCE_DIR" -DFAIRSHAPE_WITH_TBB=OFF -DFAIRSHAPE_WITH_VTK=OFF -DFAIRSHAPE_WITH_CGAL=OFF \
  -DFAIRSHAPE_WITH_CERES=OFF -DFAIRSHAPE_WITH_PETSC=OFF -DFAIRSHAPE_WARNINGS_AS_ERRORS=ON > "$S/cmake-no-tbb.txt" 2>&1 \
  || { tail -30 "$S/cmake-no-tbb.txt" >&2; fail "configure without TBB"; }
if grep -qE '^TBB_DIR:' "$T/CMakeCache.txt"; then fail "TBB was searched for with FAIRSHAPE_WITH_TBB=OFF"; fi
targets=$(ninja -C "$T" -t targets all | cut -d: -f1)
for t in libfairshape_subdivision.a libfairshape_energy.a libfairshape_design.a libfairshape_solver.a; do
  echo "$targets" | grep -q "$t" || fail "$t is not generated without TBB"
done
for t in fairshape_subdivision fairshape_energy fairshape_design; do
  # What TBB would bring, as tokens (not any "tbb" substring: a clone or scratch path may contain
  # one, as CI's did): the optimized back end's *_tbb.cpp sources (refine_topology_tbb.cpp is shared
  # by both back ends), the definition turned on, a TBB library, target or header directory.
  named=$(ninja -C "$T" -t commands "$t" | tr ' ' '\n' | sed 's/refine_topology_tbb//g' \
    | grep -E '_tbb\.cpp|FAIRSHAPE_WITH_TBB=1|(^-l|/lib)tbb|TBB::|/(tbb|oneapi)/' | sort -u | head -5 || true)
  if [ -n "$named" ]; then fail "$t's commands name TBB without it: $named"; fi
done
cmake --build "$T" -j 2 --target fairshape_subdivision fairshape_energy reference_cube optimized_refused > "$S/build-no-tbb.txt" 2>&1 \
  || { tail -30 "$S/build-no-tbb.txt" >&2; fail "build subdivision and energy without TBB"; }
"$T/bin/reference_cube" > "$S/reference_cube.txt" || { cat "$S/reference_cube.txt" >&2; fail "the reference back end without TBB"; }
"$T/bin/optimized_refused" > "$S/optimized_refused.txt" || { cat "$S/optimized_refused.txt" >&2; fail "Backend::Optimized without TBB"; }
echo "minimal_deps: ok"
