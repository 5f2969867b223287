#!/usr/bin/env bash
# The reliability review's reproductions (docs/reviews: N1-N15), each run once as the review ran
# it, under a 1 GiB address-space limit and a 120 s wall limit: what it printed first, its exit
# code, its wall time and its peak memory (GNU time). Needs a release build and GNU time
# (`apt-get install time`). Prints a Markdown table.
#   scripts/bounded_table.sh
set -u
B="$(cd "$(dirname "$0")/.." && pwd)/target/release/rattleback"
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
"$B" presets show subcritical | sed 's/iz = 1.0/iz = 1e-12/' > "$T/tiny-iz.toml"
row() {
  local what="$1"; shift
  { /usr/bin/time -f "@@ %e %M" timeout 120 sh -c "ulimit -v 1048576; exec \"$B\" $*" > "$T/out" 2> "$T/err"; } 2>/dev/null
  local code=$?
  local e m
  e=$(grep -o '@@ [0-9.]* [0-9]*' "$T/err" | awk '{print $2}')
  m=$(grep -o '@@ [0-9.]* [0-9]*' "$T/err" | awk '{print $3}')
  local said
  said=$(grep -v '@@' "$T/err" | head -1 | cut -c1-90)
  [ -z "$said" ] && said="(output: $(head -c 60 "$T/out" | tr '\n' ' '))"
  printf '| %s | `%s` | %s | %s s | %s MB | %s |\n' "$what" "$*" "$code" "${e:-?}" "$(( ${m:-0} / 1024 ))" "$said"
}
echo "| review | command | exit | wall | peak | first line of stderr |"
echo "|---|---|---|---|---|---|"
row N5 "simulate --preset kapitza-upright --set pendulum.b=1e6"
row N5 "simulate --preset kapitza-upright --set initial.theta_dot=1e9"
row N5 "simulate --preset kapitza-upright --set pendulum.b=1e10"
row N5 "simulate --preset kapitza-upright --set pendulum.b=1e300"
row N13 "simulate --t-end 1e12 --method strang"
row N10 "simulate --set spring.k=1e8 --t-end 9e5"
row N13 "simulate --set spring.k=5e-324 --method effective-corrected"
row N13 "simulate --method blanes-moan4 --t-end 1e6 --format json"
row N6 "study sweep --ladder 5e-324,1e308"
row N6 "study sweep --ladder 1e308"
row N6 "study sweep --ladder 1e2,1e4 --t-end 1e12"
row N1 "simulate --preset $T/tiny-iz.toml"
