# fairshape without its optional dependencies (issue 26, part 1): configured with
# FAIRSHAPE_WITH_VTK, _CGAL and _CERES off, the libraries that do not need them are generated and
# none of the subdivision, energy and design chain's compile or link commands names VTK, CGAL or
# Ceres; io (with its VTK stand-in) is built. Set by tests/CMakeLists.txt: SOURCE_DIR.
source "$(dirname "$0")/lib.sh"
S="$SCRATCH"
cmake -S "$SOURCE_DIR" -B "$S/build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DFAIRSHAPE_WITH_VTK=OFF \
  -DFAIRSHAPE_WITH_CGAL=OFF -DFAIRSHAPE_WITH_CERES=OFF > "$S/cmake.txt" 2>&1 || { tail -30 "$S/cmake.txt" >&2; fail "configure"; }
grep -q "tests, benchmarks and fuzzers need VTK, CGAL and Ceres: not built" "$S/cmake.txt" || fail "configure did not say what it leaves out"
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
echo "minimal_deps: ok"
