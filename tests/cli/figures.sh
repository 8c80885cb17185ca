#!/usr/bin/env bash
# The published figures (scripts/figures/, docs/figures/) rebuilt at a small size: each script
# runs its compares, writes README.md and results.json with a verdict per claim, and keeps one
# image per row. Usage: figures.sh PENUMBRA_BINARY DATA_DIR
set -euo pipefail
bin=$1
root=$(cd "$(dirname "$0")/../.." && pwd)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
export PENUMBRA_CACHE="$out/cache"
for figure in light-bleeding contact-hardening texel-density; do
  python3 "$root/scripts/figures/$figure.py" --small --penumbra "$bin" --out "$out/$figure"
  python3 - "$out/$figure" <<'PY'
import json, os, sys
folder = sys.argv[1]
r = json.load(open(os.path.join(folder, "results.json")))
assert r["small"] and r["rows"], "no rows"
for row in r["rows"]:
    assert 0.0 < row["rmse"] < 0.5, (row["label"], row["rmse"])
    assert os.path.getsize(os.path.join(folder, row["label"] + ".png")) > 1000, row["label"]
assert r["verdicts"] and all(isinstance(v["agrees"], bool) for v in r["verdicts"]), r["verdicts"]
readme = open(os.path.join(folder, "README.md")).read()
assert "The paper's claim" in readme and readme.count("penumbra compare") == len(r["rows"]), readme
print(folder, "ok:", ", ".join(f"{v['agrees']}" for v in r["verdicts"]))
PY
done
