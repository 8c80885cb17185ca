#!/usr/bin/env bash
# expect_error.sh PENUMBRA FILE: runs `PENUMBRA render --scene FILE --size 32x32` (the
# AddressSanitizer + UBSan build) and passes only if it exits 1 with exactly one stderr line (besides a lone model's ground notice) that
# starts "penumbra: " and names FILE, is text (UTF-8, no control characters: no bytes of the file
# echoed), writes no image, and no sanitizer reported anything.
set -u
bin=$1
file=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# Exit codes of the sanitizers differ from the CLI's 1, so a report can never pass as an error.
export ASAN_OPTIONS=exitcode=86:detect_leaks=1:strict_string_checks=1:check_initialization_order=1
export UBSAN_OPTIONS=exitcode=87:halt_on_error=1:print_stacktrace=1
timeout 60 "$bin" render --scene "$file" --size 32x32 --out "$tmp/out.png" >"$tmp/stdout" 2>"$tmp/stderr"
rc=$?
# A lone model's ground notice (one informational line, written as the model loads) is not the error.
grep -v "no floor in the model, so a .* ground is added" "$tmp/stderr" >"$tmp/errors"; mv "$tmp/errors" "$tmp/stderr"
err=$(cat "$tmp/stderr")
fail() { echo "FAIL $file: $1"; echo "--- exit code $rc, stderr:"; cat "$tmp/stderr"; exit 1; }
[ "$rc" -eq 124 ] && fail "timed out (a hang)"
grep -qE "Sanitizer|runtime error:" "$tmp/stderr" && fail "sanitizer report"
[ "$rc" -eq 1 ] || fail "exit code $rc, expected 1"
[ "$(wc -l <"$tmp/stderr")" -eq 1 ] || fail "expected exactly one line on stderr"
iconv -f UTF-8 -t UTF-8 "$tmp/stderr" >/dev/null 2>&1 || fail "the message is not UTF-8 text (raw bytes?)"
LC_ALL=C grep -q $'[\x01-\x08\x0b-\x1f\x7f]' "$tmp/stderr" && fail "the message holds control characters"
case "$err" in "penumbra: "*) ;; *) fail "the line does not start with 'penumbra: '" ;; esac
name=$(basename "$file")
case "$err" in *"$name"*) ;; *) fail "the message does not name $name" ;; esac
[ -e "$tmp/out.png" ] && fail "an image was written"
echo "ok $name: $err"
