#!/usr/bin/env bash
# CI: fibra as a package. Installs the build tree's fibra into a scratch prefix, builds
# samples/embed against it with find_package(fibra) (without -march=native: the ABI must hold),
# runs it to the end and with an immediate cancel, and checks what each run printed and wrote;
# then configures samples/embed with fibra as a subproject (add_subdirectory) and compiles it.
#   bash tests/embed_roundtrip.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
src=$1
build=$2
work=$build/embed_roundtrip  # a fixed path, so that ccache finds the sample's object again
rm -rf "$work"
mkdir -p "$work"
cmake --install "$build" --prefix "$work/prefix" >"$work/install.log"
test -f "$work/prefix/include/fibra/fibra.h"
test -f "$work/prefix/include/fibra/engine/world.h"
test -f "$work/prefix/lib/cmake/fibra/fibraConfig.cmake" ||
  test -f "$work/prefix/lib64/cmake/fibra/fibraConfig.cmake"
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
cmake -S "$src/samples/embed" -B "$work/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$work/prefix" "${launcher[@]}" >"$work/configure.log"
cmake --build "$work/build" >"$work/build.log"

"$work/build/fibra_embed" "$src/samples/cantilever.json" "$work/out" >"$work/run.log"
cat "$work/run.log"
grep -q "^step 1 increment 10: t = 1, " "$work/run.log"
grep -q "^finished: t = 1, 11 frames in " "$work/run.log"
grep -q "^residual of the last converged state on all DOFs, the held ones. reactions included: |r| = " "$work/run.log"
for f in result.pvd result_0010.vtu history.csv final_state.csv; do test -f "$work/out/$f"; done
test "$(wc -l <"$work/out/history.csv")" -eq 11

"$work/build/fibra_embed" "$src/samples/cantilever.json" "$work/cancelled" --cancel-after 0 \
  >"$work/cancel.log"
cat "$work/cancel.log"
grep -q "^cancelled: t = 0, the last converged state written to " "$work/cancel.log"
test -f "$work/cancelled/final_state.csv"
test "$(wc -l <"$work/cancelled/history.csv")" -eq 1
if ls "$work/out" "$work/cancelled" | grep -q '\.part$'; then exit 1; fi

# add_subdirectory: the library alone, without -march=native, and the sample compiles against it
# (its one object; building the library a second time would take minutes).
cmake -S "$src/samples/embed" -B "$work/sub" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DFIBRA_SOURCE="$src" "${launcher[@]}" >"$work/sub-configure.log"
if grep -q -- "-march=native" "$work/sub/build.ninja"; then exit 1; fi
if grep -qE "^build (fibra|fibra_tests|bench_[a-z_]+):" "$work/sub/build.ninja"; then exit 1; fi
grep -q "^build fibra/libfibra.a:" "$work/sub/build.ninja"
cmake --build "$work/sub" --target CMakeFiles/fibra_embed.dir/embed.cpp.o >"$work/sub-build.log"
rm -rf "$work"
echo "embed round trip: ok"
