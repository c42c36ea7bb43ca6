#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/, docs/fuzzing.md) in their own build folder with clang and
# runs each for a while on a corpus seeded from the project's scenes and TOML files.
# `scripts/fuzz.sh --help` for the options. Exit status: 0 when no target found anything, 1 when
# one did (a crash, sanitizer report, leak, timeout or out-of-memory), 2 for a usage error.
set -euo pipefail

usage() {
  cat <<'EOF'
usage: scripts/fuzz.sh [options] [TARGET...]

Builds the fuzz targets with clang (-fsanitize=fuzzer,address,undefined) and runs each TARGET
(nff, bpt, config, sweep; default all four, one after the other) for --seconds seconds.

options:
  --seconds N      how long each target runs (libFuzzer -max_total_time; default 60)
  --jobs N         parallel build jobs (default 1)
  --build-dir DIR  the fuzz build folder (default build-fuzz; a folder of its own)
  --max-len BYTES  largest scene input (nff, bpt; default 1048576; longer seeds are truncated)
  --toml-max-len BYTES
                   largest config or sweep input (default 1048576, the readers' own limit,
                   kMaxConfigFileBytes: a 62 KB key once crashed the reader, past 16 KiB)
  --build-only     configure, build and lay out the corpora, run nothing
  -h, --help       this text

Writes under the build folder:
  fuzz-corpus/TARGET/    the working corpus: the seeds plus what libFuzzer keeps; it persists,
                         so later runs start where earlier ones stopped
  fuzz-findings/TARGET/  inputs that found something (crash-*, leak-*, timeout-*, oom-*)
  fuzz-logs/TARGET.log   libFuzzer's output
Reproduce a finding: BUILD/fuzz/TARGET_fuzz FILE (for example build-fuzz/fuzz/nff_fuzz
build-fuzz/fuzz-findings/nff/crash-...).

Needs the Debian packages clang and llvm (llvm-symbolizer, for stacks with file and line),
besides the normal build's (scripts/quickstart.sh installs those).
EOF
}

cd "$(dirname "$0")/.."
repo="$(pwd)"
seconds=60
jobs=1
build_dir=build-fuzz
max_len=1048576
toml_max_len=1048576
build_only=0
targets=()
all_targets=(nff bpt config sweep)

while (($#)); do
  case "$1" in
    --seconds | --jobs | --build-dir | --max-len | --toml-max-len)
      if (($# < 2)); then
        echo "fuzz.sh: $1 needs a value" >&2
        exit 2
      fi
      case "$1" in
        --seconds) seconds="$2" ;;
        --jobs) jobs="$2" ;;
        --build-dir) build_dir="$2" ;;
        --max-len) max_len="$2" ;;
        --toml-max-len) toml_max_len="$2" ;;
      esac
      shift 2
      ;;
    --build-only)
      build_only=1
      shift
      ;;
    -h | --help)
      usage
      exit 0
      ;;
    -*)
      echo "fuzz.sh: unknown option '$1' (see --help)" >&2
      exit 2
      ;;
    *)
      if [[ " ${all_targets[*]} " != *" $1 "* ]]; then
        echo "fuzz.sh: unknown target '$1'; expected one of: ${all_targets[*]}" >&2
        exit 2
      fi
      targets+=("$1")
      shift
      ;;
  esac
done
for n in "$seconds" "$jobs" "$max_len" "$toml_max_len"; do
  if ! [[ "$n" =~ ^[1-9][0-9]*$ ]]; then
    echo "fuzz.sh: '$n' is not a positive whole number" >&2
    exit 2
  fi
done
if ((${#targets[@]} == 0)); then targets=("${all_targets[@]}"); fi

for tool in clang clang++ cmake; do
  if ! command -v "$tool" > /dev/null; then
    echo "fuzz.sh: '$tool' not found; install the Debian packages clang and llvm" \
      "(apt-get install clang llvm)" >&2
    exit 2
  fi
done
if ! command -v llvm-symbolizer > /dev/null; then
  echo "fuzz.sh: llvm-symbolizer not found (Debian package llvm): stacks will lack file and line"
fi

# --- configure and build ---------------------------------------------------------------------
# -O1 -g without NDEBUG: libFuzzer's recommended optimisation, and assertions (glm's) stay on.
# No -Werror: a warning only clang gives must not stop a fuzzing run. No tests or benchmarks.
CC=clang CXX=clang++ cmake -S . -B "$build_dir" -DRTSIM_FUZZ=ON -DRTSIM_TESTS=OFF \
  -DRTSIM_WERROR=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g" \
  > /dev/null
build_targets=()
for t in "${targets[@]}"; do build_targets+=("${t}_fuzz"); done
nice -n 10 cmake --build "$build_dir" -j "$jobs" --target "${build_targets[@]}"

# --- corpora -----------------------------------------------------------------------------------
shared="${RTSIM_SHARED_DIR:-$repo/../shared}"
corpus_root="$build_dir/fuzz-corpus"
findings_root="$build_dir/fuzz-findings"
logs="$build_dir/fuzz-logs"
mkdir -p "$logs"

# Copies the seed files given into the target's corpus as seed-NAME (existing copies are
# refreshed; what libFuzzer added stays).
seed() {
  local target="$1"
  shift
  mkdir -p "$corpus_root/$target"
  local f
  for f in "$@"; do
    [ -f "$f" ] && install -m 0644 "$f" "$corpus_root/$target/seed-$(basename "$(dirname "$f")")-$(basename "$f")"
  done
  return 0
}
shopt -s nullglob globstar
seed nff "$shared"/scenes/*.nff tests/data/*.nff tests/data/**/*.nff fuzz/seeds/nff/*.nff
seed bpt "$shared"/scenes/*.bpt tests/data/*.bpt tests/data/**/*.bpt
# Config files: every TOML under configs/ that is not a sweep file, and the tests' configs.
config_seeds=()
for f in configs/**/*.toml; do
  case "$f" in configs/sweeps/*) ;; *) config_seeds+=("$f") ;; esac
done
seed config "${config_seeds[@]}" tests/data/params/*.toml fuzz/seeds/config/*.toml
seed sweep configs/sweeps/*.toml fuzz/seeds/sweep/*.toml
shopt -u nullglob globstar

# The TOML dictionary plus every parameter name the documentation lists.
toml_dict="$build_dir/fuzz-toml.dict"
{
  cat fuzz/toml.dict
  grep -ho '^| `[a-z][a-z0-9_.]*`' docs/parameters*.md | sed 's/^| `\(.*\)`$/"\1"/' | sort -u
} > "$toml_dict"

if ((build_only)); then
  echo "fuzz.sh: built ${build_targets[*]}; corpora in $corpus_root"
  exit 0
fi

# --- run -----------------------------------------------------------------------------------------
status=0
summary=()
for t in "${targets[@]}"; do
  dict=fuzz/nff.dict
  len="$max_len"
  case "$t" in config | sweep)
    dict="$toml_dict"
    len="$toml_max_len"
    ;;
  esac
  mkdir -p "$findings_root/$t"
  before="$(ls "$findings_root/$t" | wc -l)"
  log="$logs/$t.log"
  echo "fuzz.sh: running ${t}_fuzz for ${seconds} s (log: $log)"
  set +e
  nice -n 10 "$build_dir/fuzz/${t}_fuzz" "$corpus_root/$t" -dict="$dict" \
    -max_total_time="$seconds" -max_len="$len" -timeout=10 -rss_limit_mb=2048 \
    -artifact_prefix="$findings_root/$t/" -print_final_stats=1 > "$log" 2>&1
  rc=$?
  set -e
  after="$(ls "$findings_root/$t" | wc -l)"
  new=$((after - before))
  runs="$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)"
  # Without final stats (a crash stops the run), the last status line's count.
  [ -n "$runs" ] || runs="$(grep -o '^#[0-9]*' "$log" | tail -1 | tr -d '#')"
  speed="$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)"
  cov="$(grep -o 'cov: [0-9]* ft: [0-9]* corp: [0-9]*' "$log" | tail -1)"
  line="$t: ${runs:-?} runs (${speed:-?}/s), ${cov:-cov: ?}, exit $rc, $new new finding(s)"
  if ((rc != 0 || new > 0)); then
    status=1
    found="$(ls -t "$findings_root/$t" | head -1)"
    line+=" -> ${found:+$findings_root/$t/$found}; see $log"
  fi
  summary+=("$line")
done

echo "fuzz.sh: summary (${seconds} s per target)"
printf '  %s\n' "${summary[@]}"
exit "$status"
