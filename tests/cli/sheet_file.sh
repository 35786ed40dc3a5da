# Sheet files (configs/README.md, "Sheet files"): a sheet run saves every sheet, and a config
# can start a sheet from a saved one (`file:`) and go on designing it.
source "$(dirname "$0")/lib.sh"
S="$SCRATCH"
"$FS" run configs/welch-witkin/fig1.yaml --out "$S/fig1" 2>/dev/null || fail "fig1 failed"
id=$(sed -n 2p "$S/fig1/runs.csv" | cut -d, -f1)
saved="$S/fig1/sheets/${id}_sheet.sheet"
[ -s "$saved" ] || fail "no sheets/${id}_sheet.sheet"
head -3 "$saved" | grep -q "^format fairshape-sheet 1$" || fail "no format line"
# output.vtk: all saves every step too; the last step is the final state.
[ "$(ls "$S/fig1/sheets/${id}"_step*_sheet.sheet | wc -l)" -eq 4 ] || fail "expected a sheet file per design step"
cmp -s "$saved" "$S/fig1/sheets/${id}_step3_sheet.sheet" || fail "the last step's sheet differs from the final one"

# Reloaded with nothing to solve: the same surface (final.obj) and the same file again. The
# path is relative to the config's folder, like every input file.
cat > "$S/reload.yaml" <<YAML
name: reload
sheets:
  - {name: sheet, file: fig1/sheets/${id}_sheet.sheet}
output: {samples_per_span: 8}
YAML
"$FS" run "$S/reload.yaml" --out "$S/reload" 2>/dev/null || fail "reload failed"
cmp -s "$S/fig1/final.obj" "$S/reload/final.obj" || fail "the reloaded surface differs from the saved one"
rid=$(sed -n 2p "$S/reload/runs.csv" | cut -d, -f1)
cmp -s "$saved" "$S/reload/sheets/${rid}_sheet.sheet" || fail "the reloaded sheet saved again differs"
grep -q "${id}_sheet.sheet" "$S/reload/run.json" || fail "run.json does not list the sheet file as an input"

# The design goes on: refined further, one more constraint, about the saved rest shape.
"$FS" run "$S/reload.yaml" --out "$S/more" --set 'sheets.0.refine=[[0, 3, 3]]' \
  --set 'constraints=[{type: point, uv: [1, 1], by: [0, 0, 0.2]}, {type: point, uv: [0.125, 0.125], by: [0, 0, 0]}, {type: point, uv: [1.875, 1.875], by: [0, 0, 0]}]' \
  --set energy.alpha=0.01 --set energy.rest_shape=true 2>/dev/null || fail "a further design step failed"
grep -q ",converged," "$S/more/runs.csv" || fail "the further design step did not converge"
mid=$(sed -n 2p "$S/more/runs.csv" | cut -d, -f1)
grep -q "^layers 2$" "$S/more/sheets/${mid}_sheet.sheet" || fail "the refined sheet was not saved with two layers"

# A sheet name is never a path: the file stays in the run's sheets/ folder.
"$FS" run "$S/reload.yaml" --set 'sheets.0.name=../../escape' --out "$S/odd" 2>/dev/null || fail "odd name run failed"
[ -s "$S/odd/sheets/"*"_.._.._escape.sheet" ] || fail "odd sheet name not kept inside sheets/"
! ls "$S" | grep -q escape || fail "a sheet file was written outside the run folder"

# Refused before anything runs, naming the key or the file's line.
expect_error 2 "sheets\[0\].spans: comes from the file" -- "$FS" run "$S/reload.yaml" --set 'sheets.0.spans=[4, 4]' --dry-run
expect_error 2 "sheets\[0\].geometry: comes from the file" -- "$FS" run "$S/reload.yaml" --set sheets.0.geometry=cylinder --dry-run
expect_error 2 "sheets\[0\].file: input file 'nowhere.sheet' not found" -- \
  "$FS" run "$S/reload.yaml" --set sheets.0.file=nowhere.sheet --dry-run
expect_error 2 "sheets\[0\].refine: cannot refine span (level 1, 0, 0)" -- \
  "$FS" run "$S/reload.yaml" --set 'sheets.0.refine=[[1, 0, 0]]' --dry-run
sed 's/^format fairshape-sheet 1$/format fairshape-sheet 2/' "$saved" > "$S/v2.sheet"
expect_error 2 "v2.sheet:2: format version 2 is not supported" -- "$FS" run "$S/reload.yaml" --set sheets.0.file="$S/v2.sheet" --dry-run
sed '12s/^c \([0-9]* [0-9]* [0-9]*\) [^ ]*/c \1 nan/' "$saved" > "$S/nan.sheet"
expect_error 2 "nan.sheet:12: x is not finite" -- "$FS" run "$S/reload.yaml" --set sheets.0.file="$S/nan.sheet" --dry-run
head -c 2000 "$saved" > "$S/cut.sheet"  # the header promises more control points than follow
expect_error 2 "cut.sheet:6: a sheet of 8 x 8 base spans has at least 121 control points, more than the .* (file truncated?)" -- "$FS" run "$S/reload.yaml" --set sheets.0.file="$S/cut.sheet" --dry-run
echo "sheet_file: ok"
