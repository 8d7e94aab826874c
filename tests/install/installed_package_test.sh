#!/usr/bin/env bash
# CTest "installed_package": the package as a user's project sees it.
#   1. cmake --install BUILD --prefix TMP (the CLI, the library, headers, config, catalog);
#   2. examples/cpp configured with find_package(dynosize CONFIG) against TMP only, built (one
#      file) and run from an unrelated folder without DYNOSIZE_CATALOG: it must find TMP's
#      catalog by itself (the build's own prefix is not TMP) and fly the README's pick;
#   3. the installed CLI finds the same catalog and gives the same mission numbers;
#   3b. the installed CLI serves the installed page (share/dynosize/web) and stops on SIGINT;
#   4. with PYTHON and PY_DIR (the Python module built): the installed package dynosize imported
#      from TMP/PY_DIR finds TMP's catalog and gives the same mission numbers.
# Usage: installed_package_test.sh BUILD_DIR SOURCE_DIR [PYTHON PY_DIR]
set -euo pipefail
build_dir=$(cd "$1" && pwd)
source_dir=$(cd "$2" && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
prefix=$tmp/prefix
fail() { echo "installed_package: $1" >&2; exit 1; }

cmake --install "$build_dir" --prefix "$prefix" > "$tmp/install.log" || { cat "$tmp/install.log"; fail "install failed"; }
for f in bin/dynosize include/dynosize/dynosize.h include/dynosize/model/drive.h \
         lib/cmake/dynosize/dynosizeConfig.cmake lib/cmake/dynosize/dynosizeConfigVersion.cmake \
         share/dynosize/catalog/README.md; do
  [ -e "$prefix/$f" ] || fail "not installed: $f"
done

launcher=()
if command -v ccache > /dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
cmake -S "$source_dir/examples/cpp" -B "$tmp/build" -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_PREFIX_PATH="$prefix" "${launcher[@]}" > "$tmp/configure.log" 2>&1 \
  || { cat "$tmp/configure.log"; fail "find_package(dynosize) failed"; }
cmake --build "$tmp/build" > "$tmp/build.log" 2>&1 || { cat "$tmp/build.log"; fail "examples/cpp does not build"; }

cd "$tmp"
unset DYNOSIZE_CATALOG DYNOSIZE_CATALOG_PATH
out=$("$tmp/build/dynosize_example") || fail "dynosize_example failed"
echo "$out"
grep -q "^catalog $prefix/share/dynosize/catalog: " <<< "$out" || fail "the example did not load the installed catalog"
example_obj=$(sed -n 's/^evaluate: feasible; \(mission [0-9.]* min, [0-9.]* Wh\);.*/\1/p' <<< "$out")
[ -n "$example_obj" ] || fail "the example's pick is not feasible"

shown=$("$prefix/bin/dynosize" catalog show dc_m_365) || fail "the installed CLI cannot show dc_m_365"
grep -q "$prefix/share/dynosize/catalog/" <<< "$shown" || fail "the installed CLI did not use the installed catalog"
cli=$("$prefix/bin/dynosize" evaluate "$source_dir/examples/missions/quadcopter_1p5kg.json" --motor dc_m_365 \
      --esc dc_e_56 --prop dc_p_231 --battery dc_b_363 --cells 4) || fail "the installed CLI's evaluate failed"
cli_obj=$(sed -n 's/^  feasible; .*; \(mission [0-9.]* min, [0-9.]* Wh\),.*/\1/p' <<< "$cli")
[ "$cli_obj" = "$example_obj" ] || fail "the example's '$example_obj' differs from the CLI's '$cli_obj'"
# The installed CLI serves the installed page (docs/web.md): its folder is printed on start.
for f in index.html app.js style.css chart.min.js examples/quadcopter_1p5kg.json; do
  [ -e "$prefix/share/dynosize/web/$f" ] || fail "not installed: share/dynosize/web/$f"
done
"$prefix/bin/dynosize" serve --port 0 --quiet > "$tmp/serve.out" 2> "$tmp/serve.err" &
serve_pid=$!
for _ in $(seq 100); do grep -q "listening on" "$tmp/serve.out" && break; sleep 0.1; done
kill -INT "$serve_pid"
wait "$serve_pid" || fail "the installed serve did not stop cleanly on SIGINT: $(cat "$tmp/serve.err")"
grep -q "page $prefix/share/dynosize/web;" "$tmp/serve.out" || fail "the installed serve did not use the installed page: $(cat "$tmp/serve.out")"

if [ $# -ge 4 ]; then
  [ -e "$prefix/$4/dynosize/__init__.py" ] || fail "not installed: $4/dynosize"
  PYTHONPATH="$prefix/$4" "$3" - "$prefix" "$source_dir" << 'EOF' || fail "the installed Python module failed"
import json, subprocess, sys
import dynosize
prefix, source = sys.argv[1], sys.argv[2]
mission = source + "/examples/missions/quadcopter_1p5kg.json"
pick = ["--motor", "dc_m_365", "--esc", "dc_e_56", "--prop", "dc_p_231", "--battery", "dc_b_363", "--cells", "4"]
c = dynosize.Catalog()
assert c.folders == [prefix + "/share/dynosize/catalog"], c.folders
assert dynosize.__file__.startswith(prefix), dynosize.__file__
e = dynosize.evaluate(mission, motor="dc_m_365", esc="dc_e_56", prop="dc_p_231", battery="dc_b_363", cells=4, catalog=c)
cli = json.loads(subprocess.run([prefix + "/bin/dynosize", "evaluate", mission, *pick, "--json"], check=True,
                                capture_output=True, text=True).stdout)
assert e == cli, "the installed module's evaluate differs from the installed CLI's --json"
print("installed Python module: catalog", c.folders[0], "objective", e["objective"])
EOF
fi
echo "installed_package: 1 passed, 0 failed"
