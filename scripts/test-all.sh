#!/usr/bin/env bash
# Everything CI checks, in one place (README command 2 and .ci/run call exactly this script):
#   1. install what is missing (scripts/setup-debian.sh);
#   2. Release build (build/) and the whole test suite (ctest: the GoogleTest suite,
#      installed_package, which installs build/ into a temporary prefix and builds examples/cpp
#      against it as a user's project would, and python_module, the pytest suite of tests/python
#      run by Debian's /usr/bin/python3);
#   3. AddressSanitizer + UndefinedBehaviorSanitizer build with clang (build-asan/), which also
#      holds the libFuzzer targets of fuzz/;
#   4. a short fuzz pass over every target (scripts/fuzz.sh, DYNOSIZE_FUZZ_SECONDS in all);
#   5. under the sanitizers, the tests labelled "sanitize": unit, model, reader, bad-input and
#      fuzz-corpus suites; not the "whole_run" suites, which run the executable or whole
#      real-data campaigns over the same library code (CMakeLists.txt lists them).
# Both builds treat warnings as errors (-DDYNOSIZE_WERROR=ON), gcc's and clang's. Any failure
# stops the script with a non-zero exit code. DYNOSIZE_JOBS sets the build parallelism
# (default 2: the CI machine has 2 cores). Each stage prints its own time and the running total
# on stderr ("test-all.sh: <stage>: N s wall, C s CPU (total ...)").
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=${DYNOSIZE_JOBS:-2}
fuzz_seconds=${DYNOSIZE_FUZZ_SECONDS:-90}
# Stage times: wall clock, and the CPU time (user + system) of the stage's processes, which a
# busy machine inflates much less than the wall clock.
cpu_s() { awk -v hz="$(getconf CLK_TCK)" '{ printf "%d", ($16 + $17) / hz }' "/proc/$$/stat"; }
t0=$(date +%s)
t_stage=$t0
cpu_stage=$(cpu_s)
stamp() {
  local now cpu
  now=$(date +%s)
  cpu=$(cpu_s)
  echo "test-all.sh: $1: $(( now - t_stage )) s wall, $(( cpu - cpu_stage )) s CPU (total $(( now - t0 )) s wall, $cpu s CPU)" >&2
  t_stage=$now
  cpu_stage=$cpu
}

bash scripts/setup-debian.sh
stamp "setup"
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DDYNOSIZE_WERROR=ON
cmake --build build -j"$jobs"
stamp "Release build"
(cd build && ctest --output-on-failure --no-tests=error -j2)
stamp "Release tests"

# No Python module here (-DDYNOSIZE_PYTHON=OFF): an ASan-instrumented extension cannot be loaded
# by Debian's python3, which is not built with ASan.
# -O1: the sanitizers' recommended level (fast to compile, readable reports); assertions stay on
# (no NDEBUG) as an extra check in this build.
# A build-asan configured with another compiler cannot switch: start it afresh.
if [ -f build-asan/CMakeCache.txt ] && ! grep -q '^CMAKE_CXX_COMPILER:.*clang' build-asan/CMakeCache.txt; then
  rm -rf build-asan
fi
CXX=clang++ cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE=-O1 \
  -DDYNOSIZE_SANITIZE=ON -DDYNOSIZE_FUZZ=ON -DDYNOSIZE_BUILD_BENCHMARKS=OFF -DDYNOSIZE_PYTHON=OFF \
  -DDYNOSIZE_WERROR=ON
cmake --build build-asan -j"$jobs"
stamp "ASan/UBSan build"

bash scripts/fuzz.sh build-asan "$fuzz_seconds"
stamp "fuzz pass"

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:strict_string_checks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
(cd build-asan && ctest --output-on-failure --no-tests=error -j2 -L sanitize)
stamp "ASan/UBSan tests (label sanitize)"
