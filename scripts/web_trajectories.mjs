// The bit-for-bit check of issue 82: each case of CASES (written natively by
// `cargo run --release -p rattleback-web --example trajectories -- SEED N`) run in the module
// under Node, its CSV compared with the native one character by character (every number in it
// reads back to the same bits). Exit 1 at the first case that differs, naming it and the line.
//   node scripts/web_trajectories.mjs rattleback.wasm cases.json
import fs from "node:fs";

const [module, casesFile] = process.argv.slice(2);
const rb = (await WebAssembly.instantiate(fs.readFileSync(module), {})).instance.exports;
const cases = JSON.parse(fs.readFileSync(casesFile, "utf8"));
const samples = 64; // as the cases were written (web/examples/trajectories.rs)
let runs = 0, refusals = 0;
const scenes = new Set(), methods = new Set();
const started = Date.now();
for (const c of cases) {
  for (const ch of c.toml) rb.rb_text_push(ch.codePointAt(0));
  const n = rb.rb_trajectory(samples);
  let got = "";
  for (let i = 0; i < n; i++) got += String.fromCodePoint(rb.rb_out_char(i));
  if (got !== c.csv) {
    const a = got.split("\n"), b = c.csv.split("\n");
    let i = 0;
    while (i < a.length && a[i] === b[i]) i++;
    console.error(`web_trajectories: ${c.name}: differs at line ${i + 1}\n  native: ${b[i]}\n  module: ${a[i]}`);
    process.exit(1);
  }
  runs++;
  if (got.startsWith("error:")) refusals++;
  const model = /^# model = (.*)$/m.exec(got)?.[1] ?? "rattleback";
  const method = /^# integrated = (.*)$/m.exec(got)?.[1] ?? /^# method = (.*)$/m.exec(got)?.[1];
  scenes.add(model);
  if (method) methods.add(`${model} ${method}`);
}
console.log(`web_trajectories: ${runs} runs (${refusals} refused alike) over ${scenes.size} scenes and ${methods.size} scene-method pairs: the module's CSV equals the native one to the last bit in every case (${((Date.now() - started) / 1000).toFixed(1)} s under Node)`);
