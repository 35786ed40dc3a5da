# `fairshape schema` describes every config fairshape ships (each validates against it) and
# refuses what the run would refuse as an unknown key; `fairshape list --keys` lists the same keys.
source "$(dirname "$0")/lib.sh"
"$FS" schema "$SCRATCH/schema.json" 2>/dev/null || fail "fairshape schema"
"$FS" list --keys > "$SCRATCH/keys.txt" || fail "fairshape list --keys"
for kind in "surface_edit runs" "sheet runs" "curve runs" "feature runs"; do
  grep -q "^$kind" "$SCRATCH/keys.txt" || fail "list --keys lacks $kind"
done
grep -q "^  input.levels = 0  -- " "$SCRATCH/keys.txt" || fail "list --keys lacks input.levels with its default"
$PY - "$SCRATCH/schema.json" <<'PYEOF'
import glob, json, sys
import jsonschema, yaml
validator = jsonschema.Draft7Validator(json.load(open(sys.argv[1])))
files = sorted(glob.glob("configs/**/*.yaml", recursive=True) + glob.glob("tests/data/configs/*.yaml"))
assert len(files) > 40, files
for f in files:
    errors = list(validator.iter_errors(yaml.safe_load(open(f))))
    assert not errors, (f, jsonschema.exceptions.best_match(errors).message[:300])
# A misspelt key, top level or nested, matches no kind's schema.
doc = yaml.safe_load(open("configs/smoke/cow_nose_pull.yaml"))
for key, value in (("solvr", {"type": "cholesky"}), ("input", dict(doc["input"], levls=2))):
    bad = dict(doc, **{key: value})
    assert list(validator.iter_errors(bad)), key
PYEOF
echo "config_schema: ok"
