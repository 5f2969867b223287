#!/usr/bin/env bash
# Runs a chart in N shards under GNU parallel and merges them (issue 59; docs/charts.md).
#
#   scripts/shard-parallel.sh N OUT.json [study map arguments…]
#   e.g. scripts/shard-parallel.sh 3 chart.json --preset kapitza-upright --grid 200x100
#
# Across machines, give GNU parallel its ssh logins (RATTLEBACK_SSHLOGINFILE=hosts.txt: one
# `user@host` a line, each with `rattleback` on its PATH); the parts come back on stdout. A shard
# that fails (killed, a lost machine) is named and its part kept out; re-run it alone with
# `rattleback study map … --shard I/N > part-I.json` and merge again.
set -euo pipefail
n=$1
out=$2
shift 2
rattleback=${RATTLEBACK:-rattleback}
parts=$(mktemp -d)
trap 'rm -rf "$parts"' EXIT
ssh=()
if [ -n "${RATTLEBACK_SSHLOGINFILE:-}" ]; then
  ssh=(--sshloginfile "$RATTLEBACK_SSHLOGINFILE")
fi
# Each shard's progress goes to stderr with its label (`study map 2/3: …`); --halt stops the
# others at the first failure so that the run says which shard to re-run.
# shellcheck disable=SC2016
parallel "${ssh[@]}" --will-cite --halt now,fail=1 -j "$n" \
  "$rattleback" study map "$@" --shard '{}/'"$n" '>' "$parts"'/part-{}.json' ::: $(seq 1 "$n")
"$rattleback" study merge "$parts"/part-*.json > "$out"
