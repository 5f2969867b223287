"use strict";
// The fork of a served lecture (issue 82), on `rattleback serve --site`'s live page: `f` or
// the fork button fetches the session so far and starts the explorer's module on it
// (rattlebackExplorer, web/explorer.js), which replays it to its last line and forks there; the
// line above says where the fork started and how far the lecture (its player's status bar) has
// moved on since; `Esc` or the button goes back to the live view. `session` and `module` are
// the server's addresses (with the token). Returns { ended() }: whether the lecture ended while
// a fork was shown (the page then reloads when the reader comes back).
function rattlebackFork({ session, module }) {
  const state = document.getElementById("state");
  const live = document.getElementById("live"), fork = document.getElementById("fork");
  const forkButton = document.getElementById("fork-button");
  const liveButton = document.getElementById("live-button");
  let explorer = null, forkedAt = null, timer = null, ended = false;
  const lectureT = () => {
    const m = /\bt (\d+(?:\.\d+)?)\//.exec(document.getElementById("player").textContent);
    return m ? parseFloat(m[1]) : null;
  };
  const say = () => {
    const now = lectureT();
    const moved = now !== null
      ? " The lecture is now at t = " + now.toFixed(2) + " (moved on by " + (now - forkedAt).toFixed(2) + ")."
      : "";
    state.textContent = "Your fork, from the lecture at t = " + forkedAt.toFixed(2) +
      ": computed in this browser, the lecturer's file untouched." + moved +
      " Esc: back to the live view.";
  };
  const back = (why) => {
    if (explorer) explorer.stop();
    explorer = null; forkedAt = null;
    if (timer) clearInterval(timer);
    timer = null;
    fork.hidden = true; live.hidden = false;
    liveButton.hidden = true; forkButton.hidden = false;
    state.textContent = why || "Live: this page shows the lecturer's screen as it is recorded. f forks it into your browser.";
    if (ended && !why) location.reload();
  };
  const start = () => {
    if (explorer) return;
    state.textContent = "Forking: the lecture so far is replayed in your browser…";
    fetch(session)
      .then((r) => r.text().then((t) => { if (!r.ok) throw new Error(t.trim()); return t; }))
      .then((text) => {
        fork.hidden = false; live.hidden = true;
        liveButton.hidden = false; forkButton.hidden = true;
        explorer = rattlebackExplorer({
          screen: document.getElementById("screen"),
          buttons: document.getElementById("buttons"),
          module: new URL(module, location.href).href,
          start: { type: "fork", text },
          size: () => [80, 24],
          say: (message, bad, at) => {
            if (bad && forkedAt === null) { back("Cannot fork: " + message); return; }
            if (at !== undefined && at !== null) {
              forkedAt = at; say();
              timer = setInterval(say, 500);
            } else if (message) state.textContent = message;
          },
          keys: (e) => {
            if (e.key === "Escape") { back(); return true; }
            return false;
          },
        });
      })
      .catch((err) => back("Cannot fork: " + (err.message || err)));
  };
  forkButton.addEventListener("click", start);
  liveButton.addEventListener("click", () => back());
  // Taken before the player sees it (its own `f` is full screen), in the capture phase.
  document.addEventListener("keydown", (e) => {
    if (!explorer && e.key === "f" && !e.ctrlKey && !e.metaKey && !e.altKey) {
      e.preventDefault(); e.stopPropagation(); start();
    }
  }, true);
  return { ended: () => { ended = true; return explorer !== null; } };
}
