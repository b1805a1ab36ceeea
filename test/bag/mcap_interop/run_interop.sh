#!/usr/bin/env bash
# The MCAP interop test: a recording of every teleop type, written by teleop's own MCAP writer in
# each compression, read by the MCAP project's reader (@mcap/core), indexed and streamed, every
# message decoded with the ros2msg schema the file carries.
#   run_interop.sh WRITE_SAMPLE_MCAP NPM_DIR WORK_DIR
set -euo pipefail
writer=$1 npm_dir=$2 work=$3
here="$(cd "$(dirname "$0")" && pwd)"
if [ ! -d "$npm_dir/node_modules/@mcap/core" ]; then
  echo "run_interop: no @mcap/core in $npm_dir/node_modules: run scripts/setup.sh (it installs the test's npm packages)" >&2
  exit 1
fi
rm -rf "$work" && mkdir -p "$work"
export TELEOP_NPM_DIR="$npm_dir"
for compression in zstd lz4 none; do
  file="$work/samples_$compression.mcap"
  "$writer" "$file" "$compression"
  for mode in indexed streamed; do
    node "$here/read_mcap.mjs" "$file" "$mode" --min-messages 36 --topics 12 --check-samples
  done
done
