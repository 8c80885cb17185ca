#!/usr/bin/env bash
# run_fuzz.sh FUZZER TARGET CORPUS SEEDS ARTIFACTS SEED RUNS SECONDS: one fuzz.* test. Starts from
# an empty CORPUS (recreated) and the committed SEEDS, so that with SEED > 0 and RUNS > 0 a run is
# the same sequence of inputs on every machine: a failure in CI is a failure here. SECONDS caps the
# run (reached first only on a slow or busy machine). SEED 0 and RUNS 0: libFuzzer's own random
# seed for SECONDS, for fuzzing sessions (cmake -DPENUMBRA_FUZZ_RUNS=0 -DPENUMBRA_FUZZ_SEED=0).
# On a failure the last lines name the crashing input and give it in base64, so the end of a log
# is enough to reproduce it.
set -u
fuzzer=$1 target=$2 corpus=$3 seeds=$4 artifacts=$5 seed=$6 runs=$7 seconds=$8
rm -rf "$corpus" && mkdir -p "$corpus" "$(dirname "$artifacts")" || exit 2
before=$(date +%s)
PENUMBRA_FUZZ_TARGET=$target "$fuzzer" -seed="$seed" -runs="$([ "$runs" -gt 0 ] && echo "$runs" || echo -1)" \
  -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=65536 -print_final_stats=1 \
  -artifact_prefix="$artifacts" "$corpus" "$seeds"
rc=$?
if [ "$rc" -ne 0 ]; then
  for f in $(find "$(dirname "$artifacts")" -maxdepth 1 -newermt "@$before" -name "$(basename "$artifacts")*" -type f); do
    echo "crashing input: $f ($(stat -c %s "$f") bytes); rerun: PENUMBRA_FUZZ_TARGET=$target $fuzzer $f"
    echo "base64: $(base64 -w0 "$f" | head -c 8000)"
  done
fi
exit "$rc"
