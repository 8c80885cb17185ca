#!/usr/bin/env bash
# expect_render.sh PENUMBRA SCENE...: renders each SCENE (a built-in name, a scene file or a
# model file; "--builtin" stands for every built-in scene that `PENUMBRA list --json` names) with
# the AddressSanitizer + UBSan build, `PENUMBRA render --scene SCENE --size 32x32`, and passes
# only if every run exits 0, writes its PNG and no sanitizer reported anything (leaks included:
# penumbra_asan keeps the GL driver mapped until exit, see KeepLibrariesLoaded.cpp).
set -u
bin=$1
shift
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# intercept_tls_get_addr=0: GCC 12's LeakSanitizer records the driver's dynamic TLS blocks through
# __tls_get_addr and, depending on where the loader placed them, kept a bogus range that its exit
# scan then read ("Tracer caught signal 11", a fatal error, on the box-on-ground scene files, in
# fresh output folders only). Leaks are still detected: those blocks are the driver's, kept
# reachable by KeepLibrariesLoaded.cpp.
export ASAN_OPTIONS=exitcode=86:detect_leaks=1:strict_string_checks=1:check_initialization_order=1:intercept_tls_get_addr=0
export UBSAN_OPTIONS=exitcode=87:halt_on_error=1:print_stacktrace=1
scenes=()
for s in "$@"; do
  if [ "$s" = "--builtin" ]; then
    names=$("$bin" list --json | sed -n 's/^ *"name": "\(.*\)",\{0,1\}$/\1/p')
    [ -n "$names" ] || { echo "FAIL: list --json named no built-in scene"; exit 1; }
    for n in $names; do scenes+=("$n"); done
  else
    scenes+=("$s")
  fi
done
status=0
for scene in "${scenes[@]}"; do
  rm -f "$tmp/out.png"
  timeout 300 "$bin" render --scene "$scene" --size 32x32 --shadow-map 1024 --out "$tmp/out.png" >"$tmp/stdout" 2>"$tmp/stderr"
  rc=$?
  why=""
  if [ "$rc" -eq 124 ]; then why="timed out"
  elif grep -qE "Sanitizer|runtime error:" "$tmp/stderr"; then why="sanitizer report"
  elif [ "$rc" -ne 0 ]; then why="exit code $rc"
  elif [ ! -s "$tmp/out.png" ]; then why="no image written"
  fi
  if [ -n "$why" ]; then
    echo "FAIL $scene: $why"; echo "--- stderr:"; cat "$tmp/stderr"; status=1
  else
    echo "ok $scene: $(cat "$tmp/stdout")"
  fi
done
exit $status
