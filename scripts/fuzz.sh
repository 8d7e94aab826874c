#!/usr/bin/env bash
# Runs every libFuzzer target of fuzz/ for a fixed time, seeded from scripts/fuzz_seeds.txt.
#
#   scripts/fuzz.sh [BUILD_DIR] [TOTAL_SECONDS]     (defaults: build-asan, 90)
#
# BUILD_DIR must be configured with CXX=clang++ -DDYNOSIZE_FUZZ=ON (and DYNOSIZE_SANITIZE=ON, so
# that a memory error or undefined behaviour is a finding): scripts/test-all.sh does that.
# TOTAL_SECONDS is shared equally between the targets. The corpus each target grows is kept in
# BUILD_DIR/fuzz/corpus/<target> (so later runs start further on); a crashing input is written
# to BUILD_DIR/fuzz/artifacts/ and the script fails, printing how to reproduce it. A crash found
# becomes a test in tests/reliability/ (the input as a string in the test), then is fixed.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build-asan}
total=${2:-90}
mapfile -t targets < <(ls fuzz/*_fuzz.cc | xargs -n1 basename | sed 's/\.cc$//')
per=$(( total / ${#targets[@]} ))
[ "$per" -ge 3 ] || per=3
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
mkdir -p "$build/fuzz/artifacts"
start=$(date +%s)
for t in "${targets[@]}"; do
  exe="$build/$t"
  if [ ! -x "$exe" ]; then
    echo "fuzz.sh: $exe not built (configure $build with CXX=clang++ -DDYNOSIZE_FUZZ=ON)" >&2
    exit 1
  fi
  seeds="$build/fuzz/seeds/$t"
  corpus="$build/fuzz/corpus/$t"
  rm -rf "$seeds"
  mkdir -p "$seeds" "$corpus"
  # Symbolic links to the seed files where they lie.
  n=0
  while read -r target pattern; do
    case "$target" in ''|'#'*) continue ;; esac
    [ "$target" = "$t" ] || continue
    for f in $pattern; do
      [ -f "$f" ] || continue
      n=$((n + 1))
      ln -s "$(readlink -f "$f")" "$seeds/$n-$(basename "$f")"
    done
  done < scripts/fuzz_seeds.txt
  echo "fuzz.sh: $t: ${per} s, $n seed files, corpus $(ls "$corpus" | wc -l) inputs" >&2
  if ! "$exe" -max_total_time="$per" -max_len=16384 -timeout=10 -rss_limit_mb=2048 \
       -print_final_stats=0 -artifact_prefix="$build/fuzz/artifacts/$t-" \
       "$corpus" "$seeds" > "$build/fuzz/$t.log" 2>&1; then
    tail -n 60 "$build/fuzz/$t.log" >&2
    echo "fuzz.sh: $t FOUND A FAILURE: reproduce with $exe $build/fuzz/artifacts/$t-*" >&2
    exit 1
  fi
  grep -E "^#[0-9]+[[:space:]]+DONE" "$build/fuzz/$t.log" | tail -n 1 | sed "s/^/fuzz.sh: $t: /" >&2 || true
done
echo "fuzz.sh: ${#targets[@]} targets clean in $(( $(date +%s) - start )) s" >&2
