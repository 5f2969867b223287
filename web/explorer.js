"use strict";
// The explorer in a page: starts the module in a Web Worker (its source is the text of the
// element `#worker`), draws the screens it sends into `screen`, passes keys and the on-screen
// buttons on, and downloads a recording that `R` finished. Shared by the site's page and the
// served lecture's fork. `start` is the worker's first message (without module and size);
// `say(text)` shows a line of state; `keys(e)` may take a key first (true: taken).
// Returns { stop(), press(kind, code) }.
function rattlebackExplorer({ screen, buttons, module, start, size, say, keys }) {
  const source = document.getElementById("worker").textContent;
  const worker = new Worker(URL.createObjectURL(new Blob([source], { type: "text/javascript" })));
  let quit = false, stopped = false;
  worker.onmessage = (e) => {
    const m = e.data;
    if (m.error) say(m.error, true);
    else if (m.started) say(null, false, m.forkedAt);
    else if (m.quit) {
      quit = true;
      say("The explorer has ended (q): reload the page to start again.", true);
    } else if (m.download) {
      const url = URL.createObjectURL(new Blob([m.download.body], { type: "application/jsonl" }));
      const a = document.createElement("a");
      a.href = url; a.download = m.download.name; a.style.display = "none";
      document.body.appendChild(a); a.click(); a.remove();
      setTimeout(() => URL.revokeObjectURL(url), 60000);
      say("Recording downloaded as " + m.download.name +
          ": rattleback replay " + m.download.name + " --verify checks it on any machine.", false);
    } else if (m.html !== undefined) screen.innerHTML = m.html;
  };
  const [cols, rows] = size();
  worker.postMessage(Object.assign({ module, cols, rows }, start));
  const named = { ArrowUp: 1, ArrowDown: 2, ArrowLeft: 3, ArrowRight: 4, Enter: 9, Escape: 10,
                  Backspace: 11, PageUp: 12, PageDown: 13, Home: 14, End: 15, Tab: 16 };
  const press = (kind, code) => { if (!quit && !stopped) worker.postMessage({ type: "key", kind, code }); };
  const onKey = (e) => {
    if (stopped || e.metaKey) return;
    if (keys && keys(e)) { e.preventDefault(); return; }
    if (e.key in named) {
      let code = named[e.key];
      if (e.shiftKey && code <= 4) code += 4;
      press(3, code);
    } else if ([...e.key].length === 1) {
      press(e.ctrlKey ? 1 : e.altKey ? 2 : 0, e.key.codePointAt(0));
    } else {
      return;
    }
    e.preventDefault();
  };
  document.addEventListener("keydown", onKey);
  const clicks = [];
  for (const b of buttons.querySelectorAll("button[data-key]")) {
    const f = () => { press(0, b.dataset.key.codePointAt(0)); screen.focus(); };
    b.addEventListener("click", f);
    clicks.push([b, f]);
  }
  const onResize = () => {
    const [c, r] = size();
    if (!stopped) worker.postMessage({ type: "resize", cols: c, rows: r });
  };
  window.addEventListener("resize", onResize);
  screen.focus();
  return {
    press,
    stop() {
      stopped = true;
      worker.terminate();
      document.removeEventListener("keydown", onKey);
      window.removeEventListener("resize", onResize);
      for (const [b, f] of clicks) b.removeEventListener("click", f);
    },
  };
}
