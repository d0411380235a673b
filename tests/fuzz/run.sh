#!/usr/bin/env bash
# Builds the libFuzzer harnesses with clang (AddressSanitizer + UBSan) and runs each on its committed
# seed corpus for SECONDS seconds. Exits 1 on a crash, a hang (a run past 10 s), a leak or an input past
# the memory limit; the input that did it is in BUILD/artifacts/. Needs the main build (its generated GL
# loader headers) and clang with libFuzzer (Debian: clang-14, libclang-rt-14-dev).
#
#   tests/fuzz/run.sh                        # each harness 15 s (the CI smoke: about a minute in all)
#   tests/fuzz/run.sh --seconds 600          # the long run (10 minutes each)
#   tests/fuzz/run.sh --seconds 60 scene     # one harness: scene, splat_ply, preset, set_option, csv
#   tests/fuzz/run.sh --check                # exit 0 when clang can build fuzzers here, 77 when not
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
seconds=15
build="$root/build/fuzz"
glad="$root/build/glad/include"
check_only=0
harnesses=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --seconds) seconds="$2"; shift 2 ;;
    --build) build="$2"; shift 2 ;;
    --glad) glad="$2"; shift 2 ;;
    --check) check_only=1; shift ;;
    -h|--help) sed -n '2,12p' "$0"; exit 0 ;;
    scene|splat_ply|preset|set_option|csv) harnesses+=("$1"); shift ;;
    *) echo "run.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
[[ ${#harnesses[@]} -gt 0 ]] || harnesses=(scene splat_ply preset set_option csv)

cxx=""
for c in clang++-14 clang++; do
  if command -v "$c" >/dev/null; then cxx="$c"; break; fi
done
mkdir -p "$build/obj" "$build/artifacts"
probe="$build/probe.cpp"
echo 'extern "C" int LLVMFuzzerTestOneInput(const unsigned char*, unsigned long) { return 0; }' >"$probe"
if [[ -z "$cxx" ]] || ! "$cxx" -fsanitize=fuzzer "$probe" -o "$build/probe" 2>/dev/null; then
  echo "run.sh: no clang with libFuzzer here (apt-get install clang-14 libclang-rt-14-dev); fuzzing skipped" >&2
  exit 77
fi
[[ $check_only -eq 1 ]] && exit 0
if [[ ! -f "$glad/glad/gl.h" ]]; then
  echo "run.sh: $glad/glad/gl.h not found: build the project first (scripts/build.sh), or give --glad DIR" >&2
  exit 2
fi

launcher=()
command -v ccache >/dev/null && launcher=(ccache)
flags=(-std=c++20 -O1 -g -fno-omit-frame-pointer -fsanitize=address,undefined -fno-sanitize-recover=undefined
       "-DOITBENCH_SOURCE_DIR=\"$root\"" -I"$root/micro" -I"$glad")
# Compiles one source into BUILD/obj when it changed (or a header it names changed: make-like via -MMD).
object() {
  local src="$1" obj="$build/obj/$(echo "$1" | tr '/' '_').o"
  local dep="${obj%.o}.d" stale=0
  if [[ ! -f "$obj" || "$root/$src" -nt "$obj" ]]; then
    stale=1
  elif [[ -f "$dep" ]]; then
    for h in $(sed -e 's/\\$//' -e 's/^[^:]*://' "$dep"); do
      if [[ "$h" -nt "$obj" ]]; then stale=1; break; fi
    done
  fi
  if [[ $stale -eq 1 ]]; then
    "${launcher[@]}" "$cxx" "${flags[@]}" -fsanitize=fuzzer-no-link -MMD -MF "$dep" -c "$root/$src" -o "$obj" >&2
  fi
  echo "$obj"
}

declare -A sources=(
  [set_option]="micro/core/params.cpp micro/core/grid.cpp"
  [preset]="micro/core/presets.cpp micro/core/params.cpp micro/core/grid.cpp micro/core/text_position.cpp micro/core/files.cpp micro/core/data_dirs.cpp"
  [scene]="micro/oit/scene/scene.cpp micro/oit/splats/splat_scene.cpp micro/oit/splats/splat_ply.cpp micro/core/text_position.cpp micro/core/files.cpp micro/core/data_dirs.cpp"
  [splat_ply]="micro/oit/splats/splat_ply.cpp"
  [csv]="micro/core/csv.cpp micro/core/files.cpp"
)
declare -A libs=([scene]="-lassimp")
declare -A max_len=([scene]=65536 [splat_ply]=65536 [preset]=16384 [set_option]=512 [csv]=16384)

status=0
for h in "${harnesses[@]}"; do
  objs=()
  for s in ${sources[$h]}; do objs+=("$(object "$s")"); done
  objs+=("$(object "tests/fuzz/${h}_fuzz.cpp")")
  exe="$build/${h}_fuzz"
  "$cxx" "${flags[@]}" -fsanitize=fuzzer "${objs[@]}" ${libs[$h]:-} -o "$exe"
  corpus="$build/corpus/$h"  # new inputs go here; the committed seeds stay as they are
  mkdir -p "$corpus"
  echo "run.sh: fuzzing $h for $seconds s (seeds: tests/fuzz/corpus/$h)" >&2
  if ! (cd "$build" && ASAN_OPTIONS=detect_leaks=1 "$exe" "$corpus" "$here/corpus/$h" -max_total_time="$seconds" \
          -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=1024 -max_len="${max_len[$h]}" \
          -artifact_prefix="$build/artifacts/$h-" -print_final_stats=1 >"$build/$h.log" 2>&1); then
    echo "run.sh: $h: FAILED (log: $build/$h.log, input: $build/artifacts/$h-*)" >&2
    tail -n 40 "$build/$h.log" >&2
    status=1
  else
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$build/$h.log")
    echo "run.sh: $h: no crash, hang or memory error in ${runs:-?} runs" >&2
  fi
done
exit $status
