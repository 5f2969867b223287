// The browser explorer's module run under Node (issue 82): on PRESET, `+` ten times, `space`,
// frames of 1/30 s until the run is done, then the 80x24 screen printed as text, for `.ci/run`
// to compare with `cargo run -p rattleback-web --example screen -- PRESET` (the same explorer,
// native). Numbers only cross the module's boundary; it imports nothing.
//   node scripts/web_screen.mjs rattleback.wasm PRESET
import fs from "node:fs";

const [module, preset = "subcritical"] = process.argv.slice(2);
const rb = (await WebAssembly.instantiate(fs.readFileSync(module), {})).instance.exports;
for (const c of preset) rb.rb_name_push(c.codePointAt(0));
if (!rb.rb_start(80, 24)) {
  let why = "";
  for (let i = 0; i < rb.rb_error_len(); i++) why += String.fromCodePoint(rb.rb_error_char(i));
  console.error(`web_screen: ${why}`);
  process.exit(2);
}
const lines = () => {
  const w = rb.rb_width(), h = rb.rb_height(), out = [];
  for (let y = 0; y < h; y++) {
    let row = "";
    for (let x = 0; x < w; x++) {
      const c = rb.rb_char(y * w + x);
      if (c) row += String.fromCodePoint(c);
    }
    out.push(row);
  }
  return out;
};
for (let i = 0; i < 10; i++) rb.rb_key(0, "+".codePointAt(0));
rb.rb_key(0, " ".codePointAt(0));
let frames = 0;
const status = () => lines()[22];
while (!/│ (done|failed) │|\| (done|failed) \|/.test(status()) && frames < 1000000) {
  rb.rb_frame(1000 / 30);
  frames++;
}
process.stdout.write(lines().join("\n") + "\n");
