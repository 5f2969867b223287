// Every pane and a long run in the browser's module under Node (issue 82): the module starts
// no thread, so a pane's job (the comparison, the weak-* view, the sweep, the map) is worked a
// slice at a frame and a long run's later segments are verified in place; none may trap.
// For each scene: the pane's key, frames, play, frames; then a lecture forked with its
// horizon made long (segments verified ahead).
//   node scripts/web_panes.mjs rattleback.wasm LECTURE.jsonl
import fs from "node:fs";

const [module, lecture] = process.argv.slice(2);
const bytes = fs.readFileSync(module);
const fresh = async () => (await WebAssembly.instantiate(bytes, {})).instance.exports;
const status = (rb) => {
  const w = rb.rb_width(), y = rb.rb_height() - 2;
  let row = "";
  for (let x = 0; x < w; x++) { const c = rb.rb_char(y * w + x); if (c) row += String.fromCodePoint(c); }
  return row.trim();
};
let checked = 0;
for (const preset of ["subcritical", "kapitza-upright", "celt-clockwise", "tapping"]) {
  for (const key of ["C", "W", "B", "K", "M", "t"]) {
    const rb = await fresh();
    for (const c of preset) rb.rb_name_push(c.codePointAt(0));
    if (!rb.rb_start(100, 30)) throw new Error(`${preset}: did not start`);
    try {
      rb.rb_key(0, key.codePointAt(0));
      for (let i = 0; i < 30; i++) rb.rb_frame(33);
      rb.rb_key(0, " ".codePointAt(0));
      for (let i = 0; i < 90; i++) rb.rb_frame(33);
    } catch (e) {
      console.error(`web_panes: ${preset}, key ${key}: the module trapped: ${e}`);
      process.exit(1);
    }
    checked++;
  }
}
// A long lecture: its horizon past the first segment, so the rest is verified ahead.
const text = fs.readFileSync(lecture, "utf8").replace(/t_end = 30\.0/, "t_end = 200.0");
const rb = await fresh();
for (const c of text) rb.rb_text_push(c.codePointAt(0));
try {
  if (!rb.rb_fork(80, 24)) throw new Error("refused");
  for (let i = 0; i < 10; i++) rb.rb_key(0, "+".codePointAt(0));
  rb.rb_frame(33);
  if (/paused/.test(status(rb))) rb.rb_key(0, " ".codePointAt(0));
  for (let i = 0; i < 600 && !/done/.test(status(rb)); i++) rb.rb_frame(33);
} catch (e) {
  console.error(`web_panes: a long forked run trapped: ${e}`);
  process.exit(1);
}
if (!/t 200\.00\/200 │ done/.test(status(rb))) {
  console.error(`web_panes: the long forked run did not end: ${status(rb)}`);
  process.exit(1);
}
console.log(`web_panes: ${checked} pane openings over 4 scenes and a 200 s forked run (segments verified ahead) ran in the module without a trap: ${status(rb)}`);
