#!/usr/bin/env bash
# Runs a chart in N shards under GNU parallel and merges them (issue 59; docs/charts.md).
#
#   scripts/shard-parallel.sh N OUT.json [study map arguments…]
#   e.g. scripts/shard-parallel.sh 3 chart.json --preset kapitza-upright --grid 200x100
#
# No shell ever reads an argument (issue 66). GNU parallel joins a command into one line for a
# shell; `-q` quotes every word of it first, so a preset named `x$(touch X).toml`, `a;b.toml`,
# `my preset.toml` or one holding a quote or a newline reaches `rattleback` as one argument, and
# each part comes back through `--results` (no `>` for a shell to read). Two things `-q` does not
# quote, because parallel reads them before any shell: its replacement strings (`{}`, `{.}`,
# `{= perl =}`, …) and its input separators (`:::`, `::::`, …). An argument holding `{` or `}`,
# or equal to a separator, is refused here with its position.
#
# Across machines, give GNU parallel its ssh logins (RATTLEBACK_SSHLOGINFILE=hosts.txt, each with
# `rattleback` on its PATH); the parts come back on stdout. By parallel's design a login line is
# a command (`ssh -o ProxyCommand=… host` runs the proxy), so this script trusts none: each line
# must be `[CPUS/][USER@]HOST[:PORT]` of letters, digits, `.`, `-` and `_` (or `:` for this
# machine), blank lines and `#` comments aside, in a regular file of at most 64 KiB. A user or a
# host begins with a letter or a digit: one beginning with `-` would reach ssh as an option
# (`-Fevil.conf` reads another configuration, whose ProxyCommand runs; issue 80), and `..`, which
# parallel reads as "my own ~/.parallel/sshloginfile", is no host. Anything richer (jump hosts,
# keys) belongs in ~/.ssh/config under a host alias.
#
# A shard that fails (killed, a lost machine) is named and the merge refused; re-run it alone with
# `rattleback study map … --shard I/N > part-I.json` and merge again.
set -euo pipefail
if [ $# -lt 2 ]; then
  echo "usage: $0 N OUT.json [study map arguments…]" >&2
  exit 2
fi
n=$1
out=$2
shift 2
case $n in
  '' | *[!0-9]* | 0*)
    echo "$0: N must be a whole number from 1 to 10000, got '$n'" >&2
    exit 2
    ;;
esac
if [ "${#n}" -gt 5 ] || [ "$n" -gt 10000 ]; then
  echo "$0: N must be a whole number from 1 to 10000, got '$n'" >&2
  exit 2
fi
rattleback=${RATTLEBACK:-rattleback}
position=0
for arg in "$rattleback" "$@"; do
  case $arg in
    *'{'* | *'}'*)
      echo "$0: argument $position holds '{' or '}', which GNU parallel would read as its own replacement string; rename the file or pass the value without braces" >&2
      exit 2
      ;;
    ':::' | '::::' | ':::+' | '::::+')
      echo "$0: argument $position is '$arg', which GNU parallel reads as its input separator" >&2
      exit 2
      ;;
  esac
  position=$((position + 1))
done
ssh=()
if [ -n "${RATTLEBACK_SSHLOGINFILE:-}" ]; then
  logins=$RATTLEBACK_SSHLOGINFILE
  if [ ! -f "$logins" ] || [ "$(wc -c < "$logins")" -gt 65536 ]; then
    echo "$0: RATTLEBACK_SSHLOGINFILE must name a regular file of at most 64 KiB" >&2
    exit 2
  fi
  line_no=0
  while IFS= read -r line || [ -n "$line" ]; do
    line_no=$((line_no + 1))
    case $line in '' | '#'*) continue ;; esac
    if ! [[ $line =~ ^([0-9]+/)?(:|([A-Za-z0-9][A-Za-z0-9._-]*@)?[A-Za-z0-9][A-Za-z0-9._-]*(:[0-9]+)?)$ ]]; then
      echo "$0: $logins:$line_no: not a login of the form [CPUS/][USER@]HOST[:PORT] (GNU parallel would run it as a command); put anything richer in ~/.ssh/config under a host alias" >&2
      exit 2
    fi
  done < "$logins"
  ssh=(--sshloginfile "$logins")
fi
parts=$(mktemp -d)
trap 'rm -rf "$parts"' EXIT
# Each shard's progress goes to stderr with its label (`study map 2/3: …`); --halt stops the
# others at the first failure so that the run says which shard to re-run. Parallel prints each
# part on its stdout as well as into --results: that copy is dropped.
parallel "${ssh[@]}" --will-cite -q --halt now,fail=1 -j "$n" --results "$parts/part-{}" \
  "$rattleback" study map "$@" --shard "{}/$n" ::: $(seq 1 "$n") > /dev/null
files=()
for i in $(seq 1 "$n"); do
  files+=("$parts/part-$i")
done
"$rattleback" study merge -- "${files[@]}" > "$out"
