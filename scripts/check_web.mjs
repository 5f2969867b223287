// The site `rattleback web DIR` writes, in headless Chromium (issue 82), served by a small
// static server of this script's own on 127.0.0.1: the default preset played to its end at
// top speed shows the native explorer's status bar (STATUS, from `cargo run -p rattleback-web
// --example screen`); `?preset=kapitza-upright` opens the pendulum; the screen is text in the
// DOM (drawn by a Web Worker that runs the module); no page error; no request leaves the site; at 400x800 the screen's text is at least
// 10 CSS px high. Prints the module's size and the first screen's time on loopback.
//   node scripts/check_web.mjs DIR "STATUS LINE"
import { chromium } from "playwright-core";
import http from "node:http";
import fs from "node:fs";
import path from "node:path";

const [dir, status] = process.argv.slice(2);
const types = { ".html": "text/html; charset=utf-8", ".wasm": "application/wasm" };
const server = http.createServer((req, res) => {
  const name = new URL(req.url, "http://x").pathname === "/" ? "index.html" : new URL(req.url, "http://x").pathname.slice(1);
  const file = path.join(dir, path.basename(name));
  if (!fs.existsSync(file)) { res.writeHead(404); res.end(); return; }
  res.writeHead(200, { "content-type": types[path.extname(file)] || "application/octet-stream" });
  res.end(fs.readFileSync(file));
});
await new Promise((r) => server.listen(0, "127.0.0.1", r));
const base = `http://127.0.0.1:${server.address().port}/`;
const executablePath = process.env.CHROMIUM || "/usr/bin/chromium";
const browser = await chromium.launch({ executablePath, args: ["--no-sandbox"] });
const fail = async (message) => {
  console.error(`check_web: ${message}`);
  await browser.close();
  server.close();
  process.exit(1);
};
const open = async (query, viewport) => {
  const page = await browser.newPage({ viewport });
  const errors = [], outside = [];
  page.on("pageerror", (e) => errors.push(String(e)));
  page.on("console", (m) => { if (m.type() === "error") errors.push(m.text()); });
  // The worker's script is a blob of the page's own origin, not a request that leaves it.
  const own = (u) => u.startsWith(base) || u.startsWith("blob:" + base.slice(0, -1));
  page.on("request", (r) => { if (!own(r.url())) outside.push(r.url()); });
  const t0 = Date.now();
  await page.goto(base + query);
  await page.waitForFunction(() => document.getElementById("screen").textContent.includes("t 0.00/"),
    null, { timeout: 30000 });
  return { page, errors, outside, first: Date.now() - t0 };
};
const lines = (page) => page.evaluate(() => document.getElementById("screen").textContent.split("\n"));

// The default preset, to its end at top speed.
const a = await open("?cols=80&rows=24", { width: 1000, height: 800 });
await a.page.focus("#screen");
for (let i = 0; i < 10; i++) await a.page.keyboard.press("+");
await a.page.keyboard.press(" ");
await a.page.waitForFunction(() => document.getElementById("screen").textContent.includes("│ done │"),
  null, { timeout: 120000 }).catch(async () => fail(`never done:\n${(await lines(a.page)).join("\n")}`));
const shown = (await lines(a.page)).find((l) => l.includes("│ done │")) || "";
// The energy monitor's last digit depends on the elementary functions (sin, cos, exp), which
// are the platform's natively and Rust's own in the module: the same implementation on both is
// still to come (issue 82, item 3), so that field is shown, not compared.
const monitor = /ΔE\/E \S+/;
if (shown.replace(monitor, "ΔE/E _").trimEnd() !== status.replace(monitor, "ΔE/E _").trimEnd()) {
  await fail(`the status bar differs from the native explorer's:\n  page:   ${shown}\n  native: ${status}`);
}
console.log(`check_web: energy monitor: page ${(shown.match(monitor) || [""])[0]}, native ${(status.match(monitor) || [""])[0]}`);
console.log(`check_web: the default preset at x1024 ends with the native status bar: ${shown.trim()}`);
// `?` opens the help, and typing filters it, as in the terminal.
await a.page.keyboard.press("?");
await a.page.keyboard.type("reset");
await a.page.waitForFunction(() => document.getElementById("screen").textContent.includes("holding 'reset'"),
  null, { timeout: 10000 }).catch(async () => fail(`? then typing does not filter the help:\n${(await lines(a.page)).join("\n")}`));
console.log("check_web: ? opens the help, and typing filters it");
await a.page.keyboard.press("Escape");

// The picker lists the shipped presets; R says recording is not in the page yet.
await a.page.keyboard.press("R");
await a.page.waitForFunction(() => document.getElementById("screen").textContent.includes("not in the browser yet"),
  null, { timeout: 10000 }).catch(async () => fail(`R did not say recording is not here yet:\n${(await lines(a.page)).join("\n")}`));
await a.page.keyboard.press("Escape");
await a.page.keyboard.press("p");
await a.page.waitForFunction(() => document.getElementById("screen").textContent.includes("kapitza-upright"),
  null, { timeout: 10000 }).catch(async () => fail(`p did not list the presets:\n${(await lines(a.page)).join("\n")}`));
await a.page.keyboard.press("Escape");
console.log("check_web: p lists the presets; R says recording is not in the page yet");

// Another scene by its address.
const b = await open("?preset=kapitza-upright", { width: 1000, height: 800 });
const pendulum = (await lines(b.page)).join("\n");
if (!/Kapitza|pendulum/i.test(pendulum)) await fail(`?preset=kapitza-upright did not open the pendulum:\n${pendulum}`);
console.log("check_web: ?preset=kapitza-upright opens the pendulum");

// A lesson by its address.
const l = await open("?lesson=first-reversal", { width: 1000, height: 800 });
const step = (await lines(l.page)).join("\n");
if (!step.includes("step 1/")) await fail(`?lesson=first-reversal did not open the lesson:\n${step}`);
console.log("check_web: ?lesson=first-reversal opens the lesson at step 1");

// A phone.
const c = await open("", { width: 400, height: 800 });
const px = await c.page.evaluate(() => parseFloat(getComputedStyle(document.getElementById("screen")).fontSize));
if (!(px >= 10)) await fail(`at 400x800 the screen's text is ${px} px`);
console.log(`check_web: at 400x800 the text is ${px} px (the screen scrolls sideways)`);

for (const v of [a, b, l, c]) {
  if (v.errors.length) await fail(`page errors: ${v.errors.join("; ")}`);
  if (v.outside.length) await fail(`requests outside the site: ${v.outside.join(", ")}`);
}
const size = fs.statSync(path.join(dir, "rattleback.wasm")).size;
console.log(`check_web: module ${(size / 1024).toFixed(0)} KB; first screen ${a.first} ms on loopback; no page error, no outside request`);
await browser.close();
server.close();
