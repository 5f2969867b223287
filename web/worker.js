"use strict";
// The explorer's module runs here, in a Web Worker: a long integration never freezes the page,
// which only draws what this worker sends and passes the keys on. Messages in: start (a preset
// or a lesson), fork (a served lecture's lines), key, resize; out: the screen as HTML when it
// changed, a finished recording to download, an error, or the end. Shared by the site's page
// (`rattleback web`) and the served lecture's page (`rattleback serve --site`).
let rb = null, quit = false, last = 0, shown = "";
const color = (v) => v === 0x1000000 ? null : "#" + v.toString(16).padStart(6, "0");
const escape = (s) => s.replace(/&/g, "&amp;").replace(/</g, "&lt;").replace(/>/g, "&gt;");
const text = (n, at) => { let s = ""; for (let i = 0; i < n; i++) s += String.fromCodePoint(at(i)); return s; };
const error = () => text(rb.rb_error_len(), rb.rb_error_char);
const screen = () => {
  const w = rb.rb_width(), h = rb.rb_height();
  let html = "";
  for (let y = 0; y < h; y++) {
    let run = "", style = null;
    const flush = () => {
      if (run) html += style ? '<span style="' + style + '">' + escape(run) + "</span>" : escape(run);
      run = "";
    };
    for (let x = 0; x < w; x++) {
      const i = y * w + x;
      const code = rb.rb_char(i);
      if (code === 0) continue;
      let fg = color(rb.rb_fg(i)), bg = color(rb.rb_bg(i));
      const m = rb.rb_mods(i);
      if (m & 16) { const t = fg || "#d4d4d4"; fg = bg || "#1e1e1e"; bg = t; }
      const s = (fg ? "color:" + fg + ";" : "") + (bg ? "background:" + bg + ";" : "") +
                (m & 1 ? "font-weight:bold;" : "") + (m & 2 ? "opacity:0.7;" : "") +
                (m & 4 ? "font-style:italic;" : "") + (m & 8 ? "text-decoration:underline;" : "");
      // A glyph the monospace font may lack (Braille, arrows, symbols) is drawn from another
      // font of another width: held to one cell so that the columns stay aligned.
      if (code >= 0x2190 && !(code >= 0x2500 && code <= 0x259f)) {
        flush(); style = null;
        html += '<span class="cell" style="' + s + '">' + escape(String.fromCodePoint(code)) + "</span>";
        continue;
      }
      if (s !== style) { flush(); style = s; }
      run += String.fromCodePoint(code);
    }
    flush();
    html += "\n";
  }
  return html;
};
// The screen, sent only when it changed (a paused explorer sends nothing); then a recording
// `R` finished, if any.
const send = () => {
  const html = screen();
  if (html !== shown) { shown = html; postMessage({ html }); }
  const n = rb.rb_download_name();
  if (n) {
    const name = text(n, rb.rb_out_char);
    const body = text(rb.rb_download_text(), rb.rb_out_char);
    postMessage({ download: { name, body } });
  }
};
const frame = () => {
  if (quit) return;
  const now = performance.now();
  rb.rb_frame(Math.min(now - last, 250));
  last = now;
  send();
  setTimeout(frame, 1000 / 30);
};
const load = async (url) => {
  const reply = await fetch(url);
  if (!reply.ok) throw new Error((await reply.text()).trim() || reply.status + " " + reply.statusText);
  rb = (await WebAssembly.instantiate(await reply.arrayBuffer(), {})).instance.exports;
};
onmessage = async (e) => {
  const m = e.data;
  if (m.type === "start" || m.type === "fork") {
    try {
      await load(m.module);
    } catch (err) {
      postMessage({ error: "The explorer's module could not be loaded: " + (err.message || err) });
      return;
    }
    let ok;
    if (m.type === "fork") {
      for (const c of m.text) rb.rb_text_push(c.codePointAt(0));
      ok = rb.rb_fork(m.cols, m.rows);
    } else {
      for (const c of m.name) rb.rb_name_push(c.codePointAt(0));
      ok = m.lesson ? rb.rb_start_lesson(m.cols, m.rows) : rb.rb_start(m.cols, m.rows);
    }
    if (!ok) { postMessage({ error: error() }); return; }
    postMessage({ started: true, forkedAt: m.type === "fork" ? rb.rb_forked_at() : null });
    last = performance.now();
    frame();
  } else if (rb && m.type === "key" && !quit) {
    if (rb.rb_key(m.kind, m.code)) { quit = true; postMessage({ quit: true }); }
    else send();
  } else if (rb && m.type === "resize") {
    rb.rb_resize(m.cols, m.rows);
    send();
  }
};
