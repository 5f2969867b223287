#!/bin/bash
# Every shipped preset in tmux at a size and speed: play to the end, read the status bar.
# Usage: scripts/tmux-sweep.sh 80x24 10   (size, number of + presses: 10 is x1024, 0 is x1).
# Needs tmux and a release build on PATH as rattleback or at ./target/release/rattleback.
size=$1; speedkeys=$2
W=${size%x*}; H=${size#*x}
for p in $(ls presets | sed 's/.toml//'); do
  S=s$RANDOM
  tmux new -d -s $S -x $W -y $H "./target/release/rattleback --preset $p; sleep 30"
  sleep 0.7
  for ((i=0;i<speedkeys;i++)); do tmux send-keys -t $S '+'; done
  tmux send-keys -t $S ' '
  for i in $(seq 200); do
    sleep 0.3
    st=$(tmux capture-pane -p -t $S | tail -2 | head -1)
    case "$st" in *done*|*failed*) break;; esac
  done
  rev=$(./target/release/rattleback simulate --preset $p --format json | python3 -c 'import json,sys; d=json.load(sys.stdin); print(d["reversals"]["count"], d["effective"].get("reversals", {}).get("count","?") if isinstance(d["effective"].get("reversals"),dict) else "", "%.1e"%d["energy"]["max_relative_error"])')
  echo "$p | $st | simulate: $rev"; tmux kill-session -t $S
done

