#!/usr/bin/env bash
# The follower's lag behind the lecturer, measured as a user sees it: a lecturer records
# `soft-spring` at x1 in one tmux window, a student runs `follow` in another (locally, or through
# the command prefix given, e.g. `ssh -t -p 2222 root@127.0.0.1 rattleback`), and both status bars
# are read SAMPLES times while it plays: the student's first, then the lecturer's, so a positive
# difference is lag and a negative one would be a follower ahead of the lecturer.
#   scripts/follow_lag.sh [FOLLOWER-COMMAND] [SAMPLES]
# Needs tmux and a release build (cargo build --release). Prints the median, p90 and max lag in
# seconds (at x1, displayed simulated time equals wall time) and the largest lead.
set -euo pipefail
B="$(cd "$(dirname "$0")/.." && pwd)/target/release/rattleback"
FOLLOWER="${1:-$B}"
SAMPLES="${2:-40}"
DIR="$(mktemp -d)"
trap 'tmux kill-session -t rb-lec 2>/dev/null || true; tmux kill-session -t rb-stu 2>/dev/null || true; rm -rf "$DIR"' EXIT
tmux new -d -s rb-lec -x 80 -y 24 "$B --preset soft-spring --record $DIR/lag.jsonl"
sleep 0.7
tmux new -d -s rb-stu -x 80 -y 24 "$FOLLOWER follow $DIR/lag.jsonl"
sleep 1.5
tmux send-keys -t rb-lec ' '
sleep 1
for _ in $(seq 1 "$SAMPLES"); do
  b=$(tmux capture-pane -p -t rb-stu | grep -o 't [0-9.]*/' | head -1 || true)
  a=$(tmux capture-pane -p -t rb-lec | grep -o 't [0-9.]*/' | head -1 || true)
  echo "$a $b"
  sleep 0.13
done | python3 -c '
import sys
d = []
for line in sys.stdin:
    p = line.replace("t ", "").replace("/", "").split()
    if len(p) == 2:
        d.append(float(p[0]) - float(p[1]))
d.sort()
print("samples %d  lag median %.3f s  p90 %.3f s  max %.3f s  largest lead %.3f s" % (
    len(d), d[len(d) // 2], d[int(len(d) * 0.9)], d[-1], max(0.0, -d[0])))
'
