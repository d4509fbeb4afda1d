#!/usr/bin/env bash
# Builds PriMo's fuzz targets (fuzz/, docs/reliability.md) with clang, libFuzzer, AddressSanitizer
# and UndefinedBehaviorSanitizer into build-fuzz/, replays the committed regression inputs, then
# runs every target for SECONDS (default 60) on its seeds and the corpus kept from earlier runs.
#
#   scripts/fuzz.sh [SECONDS] [TARGET...]     e.g. scripts/fuzz.sh 600, scripts/fuzz.sh 30 fuzz_ply
#
# Exits non-zero on any finding (a crash, a sanitizer report, an exception other than
# primo::Error, an input slower than 10 s, an allocation above 1 GB or 2.5 GB resident); the
# input that triggered it is saved as build-fuzz/findings/<target>-crash-... Prints a table of
# executions and corpus sizes (also written to build-fuzz/fuzz-summary.md).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
seconds=${1:-60}
shift || true
build=${PRIMO_FUZZ_BUILD_DIR:-"$root/build-fuzz"}
targets=("$@")
if ((${#targets[@]} == 0)); then
  targets=(fuzz_obj fuzz_off fuzz_ply fuzz_stl fuzz_om fuzz_gltf fuzz_glb fuzz_fbx fuzz_dae fuzz_3mf
           fuzz_scenario fuzz_session fuzz_script fuzz_deformer)
fi

"$root/scripts/setup.sh" >/dev/null
# -O1 with assertions on (no NDEBUG): Eigen's and OpenMesh's index checks are findings too.
CC=clang CXX=clang++ cmake -S "$root" -B "$build" -G Ninja -DPRIMO_FUZZ=ON \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" >/dev/null
cmake --build "$build" -j "$(nproc)" --target "${targets[@]}"

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:allocator_may_return_null=0}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$root/fuzz/lsan.supp}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
mkdir -p "$build/findings"
summary="$build/fuzz-summary.md"
{
  echo "| target | seconds | executions | exec/s | corpus (files) | coverage | result |"
  echo "|---|---|---|---|---|---|---|"
} >"$summary"
failed=()

# Seeds kept in the repository's assets, besides fuzz/seeds/<name>.
extra_seeds() {
  case "$1" in
    obj) echo "$root/assets/meshes/spot_control_mesh.obj $root/../shared/spec/examples/cylinder-small.obj" ;;
    off) echo "$root/../shared/spec/examples/hexsphere.off" ;;
    fbx) echo "$root/assets/meshes/huesitos.fbx" ;;
    scenario) echo "$root/assets/scenarios/bar-bend.json $root/assets/scenarios/spot-pose.json $root/assets/scenarios/cylinder-bend-twist.json $root/../shared/spec/examples/cylinder-small-bend-45.json $root/../shared/spec/examples/hexsphere-orientation.json" ;;
    session) echo "$root/assets/sessions/spot-pose.session.json" ;;
    script) echo "$root/assets/sessions/spot-pose.script.txt" ;;
  esac
}

for target in "${targets[@]}"; do
  name=${target#fuzz_}
  binary="$build/fuzz/$target"
  corpus="$build/corpus/$name"
  seeds="$build/seeds/$name"
  mkdir -p "$corpus" "$seeds"
  cp "$root/fuzz/seeds/$name"/* "$seeds/" 2>/dev/null || true
  [[ $name == deformer ]] && cp "$root/fuzz/seeds/scenario"/* "$seeds/" 2>/dev/null || true
  for f in $(extra_seeds "$name"); do [[ -f $f ]] && cp "$f" "$seeds/"; done
  case "$name" in
    obj | off | ply | stl | om | gltf | fbx | dae | 3mf) dict="$root/fuzz/dict/$name.dict" ;;
    glb) dict="$root/fuzz/dict/gltf.dict" ;;
    scenario | session | deformer) dict="$root/fuzz/dict/json.dict" ;;
    script) dict="$root/fuzz/dict/script.dict" ;;
  esac
  log="$build/findings/$target.log"
  # Scene files are larger (the FBX seeds are 17 and 112 kB).
  case "$name" in gltf | glb | fbx | dae | 3mf) max_len=131072 ;; *) max_len=16384 ;; esac
  options=(-timeout=10 -rss_limit_mb=2560 -malloc_limit_mb=1024 -max_len=$max_len
           -dict="$dict" -artifact_prefix="$build/findings/$target-" -print_final_stats=1)
  result=ok
  # The inputs earlier fuzzing found (fuzz/regressions/<name>), each run once.
  regressions=("$root/fuzz/regressions/$name"/*)
  if [[ -e ${regressions[0]} ]] && ! "$binary" "${options[@]}" "${regressions[@]}" >"$log" 2>&1; then
    result="FINDING (regression input)"
  fi
  if [[ $result == ok ]] &&
     ! "$binary" "${options[@]}" -max_total_time="$seconds" "$corpus" "$seeds" >>"$log" 2>&1; then
    result="FINDING"
  fi
  executions=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | tail -1 | grep -o '[0-9]*$' || echo 0)
  rate=$(grep -o 'stat::average_exec_per_sec: *[0-9]*' "$log" | tail -1 | grep -o '[0-9]*$' || echo 0)
  coverage=$(grep -o 'cov: [0-9]* ft: [0-9]*' "$log" | tail -1 || echo "")
  files=$(find "$corpus" -type f | wc -l)
  echo "| $target | $seconds | $executions | $rate | $files | $coverage | $result |" >>"$summary"
  echo "fuzz: $target: $executions executions, corpus $files files, $coverage: $result"
  if [[ $result != ok ]]; then
    failed+=("$target")
    grep -E "ERROR|SUMMARY|runtime error|Test unit written|uncaught|deadly|timeout|leak" "$log" | head -20 || true
  fi
done

cat "$summary"
if ((${#failed[@]} > 0)); then
  echo "fuzz: findings in ${failed[*]} (logs and inputs in $build/findings)"
  exit 1
fi
echo "fuzz: no findings in ${#targets[@]} targets"
