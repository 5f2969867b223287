#!/usr/bin/env bash
# One build for the README's two commands (issue 68): every package the program is built with
# must get the same features when the tests' dependencies join it, or `cargo test --release`
# rebuilds it (and the program) after `cargo run --release`. Prints each difference; exit 1 if any.
set -euo pipefail
cd "$(dirname "$0")/.."
features() {
  cargo tree --quiet "${@:2}" -e "$1" --prefix none -f '{p} {f}' --target all \
    | awk '$2 ~ /^v[0-9]/ {
        key = $1 " " $2
        seen[key] = 1
        if (NF >= 3 && $3 !~ /^\(/) { n = split($3, f, ","); for (i = 1; i <= n; i++) feat[key, f[i]] = 1 }
      }
      END {
        for (k in seen) {
          line = k ":"
          for (kf in feat) { split(kf, p, SUBSEP); if (p[1] == k) line = line " " p[2] }
          print line
        }
      }' \
    | while read -r line; do
        key=${line%%:*}; rest=${line#*:}
        echo "$key:$(tr ' ' '\n' <<< "$rest" | sed '/^$/d' | sort | tr '\n' ' ')"
      done | sort
}
# The program alone (`cargo run --release` builds the package `rattleback`), then everything
# `cargo test --release` builds: both packages of the workspace with their tests' dependencies.
program=$(features features,normal,build -p rattleback)
tests=$(features features,normal,build,dev --workspace)
drift=$(join -t: <(echo "$program") <(echo "$tests") | awk -F: '$2 != $3')
if [ -n "$drift" ]; then
  echo "features the tests add to the program's dependencies (name version: program's, with tests'):"
  echo "$drift"
  echo "add them to [dependencies] in Cargo.toml (see the comment there), or cargo test rebuilds the program"
  exit 1
fi
echo "the tests add no feature to the program's dependencies"
