#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, ASan + UBSan, fuzz/) into build-fuzz/
# and runs each for SECONDS (default 30). Fails when any target finds a crash,
# a sanitizer report, a hang (one input over 5 s), a leak or an input needing
# more than 2 GiB; the input that did it is left in build-fuzz/artifacts/.
#
#   scripts/fuzz.sh [SECONDS] [TARGET...]     e.g. scripts/fuzz.sh 600 sdl_fuzz
#
# Seeds come from tests/data/, scenes/ and fuzz/seeds/, and from the corpus of
# real SDL scenes when VKRAY_SDL_CORPUS names its folder; they are copied into
# build-fuzz/seeds/. What the fuzzers learn grows build-fuzz/corpus/ from run
# to run. Nothing is written outside build-fuzz/.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-30}"
shift || true
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(sdl_fuzz mesh3vn_fuzz outline_fuzz image_fuzz)

scripts/install-deps.sh
cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_COMPILER=clang++ -DVKRAY_FUZZ=ON -DVKRAY_TESTS=OFF -DVKRAY_BENCHMARKS=OFF \
  >/dev/null
cmake --build build-fuzz --target vkray_fuzzers

# tests/data: scenes (*.dat), meshes (*.3vn) and extrude outlines (*_outline.dat).
data_scenes=() data_outlines=()
for f in tests/data/*.dat; do
  case "$f" in *_outline.dat) data_outlines+=("$f") ;; *) data_scenes+=("$f") ;; esac
done
corpus_scenes=() corpus_meshes=() corpus_outlines=()
corpus="${VKRAY_SDL_CORPUS:-}"
if [ -n "$corpus" ] && [ -d "$corpus" ]; then
  corpus_scenes=("$corpus"/bookScene.dat "$corpus"/castle.dat "$corpus"/hlScene1.dat)
  corpus_meshes=("$corpus"/*.3vn)
  corpus_outlines=("$corpus"/hlArch.dat)
elif [ -n "$corpus" ]; then
  echo "fuzz: VKRAY_SDL_CORPUS='$corpus' is not a folder; seeds from the repository only" >&2
fi
seed() {  # seed TARGET FILE...: fresh copies, so a changed source seed is seen
  local dir="build-fuzz/seeds/$1"
  shift
  rm -rf "$dir" && mkdir -p "$dir"
  for f in "$@"; do [ -f "$f" ] && cp "$f" "$dir/"; done
  return 0
}
seed sdl_fuzz "${corpus_scenes[@]}" "${data_scenes[@]}" scenes/*.sdl fuzz/seeds/sdl/*
seed mesh3vn_fuzz "${corpus_meshes[@]}" tests/data/*.3vn fuzz/seeds/mesh/*
seed mesh_import_fuzz fuzz/seeds/mesh_import/*
seed outline_fuzz "${corpus_outlines[@]}" "${data_outlines[@]}" fuzz/seeds/outline/*
seed image_fuzz fuzz/seeds/image/*

# Per target: longest input, dictionary. Limits keep each run quick; the
# readers' own limits are tested at full size in the normal test suite.
declare -A max_len=([sdl_fuzz]=4096 [mesh3vn_fuzz]=4096 [mesh_import_fuzz]=4096
                    [outline_fuzz]=1024 [image_fuzz]=4096)
declare -A dict=([sdl_fuzz]=fuzz/sdl.dict [mesh3vn_fuzz]=fuzz/numbers.dict
                 [mesh_import_fuzz]=fuzz/mesh_import.dict [outline_fuzz]=fuzz/numbers.dict [image_fuzz]=fuzz/image.dict)

# Sanitizer reports are fatal; libFuzzer itself checks leaks after each input.
export ASAN_OPTIONS="halt_on_error=1:abort_on_error=1:print_stacktrace=1:detect_leaks=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
export LSAN_OPTIONS="suppressions=$PWD/scripts/lsan.supp:print_suppressions=0"

failed=0
summary=()
for t in "${targets[@]}"; do
  mkdir -p "build-fuzz/corpus/$t" "build-fuzz/artifacts/$t" "build-fuzz/logs"
  log="build-fuzz/logs/$t.log"
  echo "fuzz: $t for ${seconds}s (log: $log)"
  status=0
  build-fuzz/fuzz/"$t" "build-fuzz/corpus/$t" "build-fuzz/seeds/$t" \
    -max_total_time="$seconds" -max_len="${max_len[$t]}" -dict="${dict[$t]}" \
    -timeout=5 -rss_limit_mb=2048 -malloc_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="build-fuzz/artifacts/$t/" >"$log" 2>&1 || status=$?
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  if [ "$status" -ne 0 ]; then
    failed=$((failed + 1))
    summary+=("$t: FAILED (exit $status) after ${runs:-?} runs; input: $(ls -t "build-fuzz/artifacts/$t" | head -1)")
    echo "---- last lines of $log:"
    tail -40 "$log"
    echo "---- reproduce: build-fuzz/fuzz/$t build-fuzz/artifacts/$t/<file>"
  else
    summary+=("$t: ok, ${runs:-?} runs in ${seconds}s")
  fi
done

printf '%s\n' "${summary[@]}"
echo "fuzz: $(( ${#targets[@]} - failed )) passed, $failed failed"
[ "$failed" -eq 0 ]
