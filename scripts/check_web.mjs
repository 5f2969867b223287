// The site `rattleback web DIR` writes, in headless Chromium (issue 82), served by a small
// static server of this script's own on 127.0.0.1: the default preset played to its end at
// top speed shows the native explorer's status bar (STATUS, from `cargo run -p rattleback-web
// --example screen`); `?preset=kapitza-upright` opens the pendulum; the screen is text in the
// DOM (drawn by a Web Worker that runs the module); no page error; no request leaves the site; at 400x800 the screen's text is at least
// 10 CSS px high; a recording made in the page (R, play, R) downloads and passes
// `RATTLEBACK replay FILE --verify`; on `RATTLEBACK serve LECTURE --site DIR`'s live page, f
// forks the lecture into the page's explorer and Esc returns to the live view, and at 400x800
// that page's text is at least 10 px too. Prints the
// module's size and the first screen's time on loopback.
//   node scripts/check_web.mjs DIR "STATUS LINE" RATTLEBACK LECTURE.jsonl
import { chromium } from "playwright-core";
import http from "node:http";
import fs from "node:fs";
import path from "node:path";
import os from "node:os";
import { execFileSync, spawn } from "node:child_process";

const [dir, status, rattleback, lecture] = process.argv.slice(2);
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
// Every field, the energy monitor's last digit included: the module and the native build take
// the same elementary functions (physics::numerics::elementary).
if (shown.trimEnd() !== status.trimEnd()) {
  await fail(`the status bar differs from the native explorer's:\n  page:   ${shown}\n  native: ${status}`);
}
console.log(`check_web: the default preset at x1024 ends with the native status bar: ${shown.trim()}`);
// `?` opens the help, and typing filters it, as in the terminal.
await a.page.keyboard.press("?");
await a.page.keyboard.type("reset");
await a.page.waitForFunction(() => document.getElementById("screen").textContent.includes("holding 'reset'"),
  null, { timeout: 10000 }).catch(async () => fail(`? then typing does not filter the help:\n${(await lines(a.page)).join("\n")}`));
console.log("check_web: ? opens the help, and typing filters it");
await a.page.keyboard.press("Escape");

// The picker lists the shipped presets.
await a.page.keyboard.press("p");
await a.page.waitForFunction(() => document.getElementById("screen").textContent.includes("kapitza-upright"),
  null, { timeout: 10000 }).catch(async () => fail(`p did not list the presets:\n${(await lines(a.page)).join("\n")}`));
await a.page.keyboard.press("Escape");
console.log("check_web: p lists the presets");

// A recording made in the page: R, faster, play, a pause, a step, the selected value up (a new
// run), play to the end, R again: the page downloads it, and the native binary verifies it.
const r = await open("?preset=subcritical&cols=80&rows=24", { width: 1000, height: 800 });
await r.page.focus("#screen");
await r.page.keyboard.press("R");
await r.page.waitForFunction(() => document.getElementById("screen").textContent.includes("recording to"),
  null, { timeout: 10000 }).catch(async () => fail(`R did not start a recording:\n${(await lines(r.page)).join("\n")}`));
for (let i = 0; i < 10; i++) await r.page.keyboard.press("+");
for (const k of [" ", " ", ".", "l", " "]) { await r.page.keyboard.press(k); await r.page.waitForTimeout(150); }
await r.page.waitForFunction(() => document.getElementById("screen").textContent.includes("│ done │"),
  null, { timeout: 120000 }).catch(async () => fail(`the recorded run never ended:\n${(await lines(r.page)).join("\n")}`));
const downloaded = r.page.waitForEvent("download", { timeout: 20000 });
await r.page.keyboard.press("R");
const download = await downloaded.catch(async () => fail(`R again downloaded nothing:\n${(await lines(r.page)).join("\n")}`));
const saved = path.join(fs.mkdtempSync(path.join(os.tmpdir(), "rattleback-web-")), download.suggestedFilename());
await download.saveAs(saved);
let verified;
try {
  verified = execFileSync(rattleback, ["replay", saved, "--verify"], { encoding: "utf8", stdio: ["ignore", "pipe", "pipe"] });
} catch (e) {
  await fail(`the page's recording ${saved} does not verify natively:\n${e.stdout}${e.stderr}`);
}
console.log(`check_web: a recording made in the page (${download.suggestedFilename()}) verifies natively: ${verified.trim().split("\n").find((l) => /checkpoint/.test(l)) || verified.trim()}`);

// Fork a served lecture: a lecture being recorded (its end line not written yet), served
// with the site's module; f forks it into the page, Esc returns to the live view.
const live = path.join(path.dirname(saved), "live.jsonl");
const lectureLines = fs.readFileSync(lecture, "utf8").split("\n").filter((l) => l && !l.includes('"kind":"end"'));
fs.writeFileSync(live, lectureLines.slice(0, 30).join("\n") + "\n");
const serving = spawn(rattleback, ["serve", live, "--site", dir], { stdio: ["pipe", "pipe", "ignore"] });
const address = await new Promise((res) => serving.stdout.once("data", (d) => res(String(d).split("\n")[0].trim())));
const f = await browser.newPage({ viewport: { width: 1100, height: 900 } });
const fErrors = [];
f.on("pageerror", (e) => fErrors.push(String(e)));
await f.goto(address);
await f.waitForFunction(() => /\bt \d+\.\d+\//.test(document.getElementById("player").textContent),
  null, { timeout: 30000 }).catch(async () => fail("the live page showed no lecture"));
await f.keyboard.press("f");
await f.waitForFunction(() => document.getElementById("screen").textContent.includes("forked at t") &&
  document.getElementById("state").textContent.includes("Your fork, from the lecture at t ="),
  null, { timeout: 60000 }).catch(async () => fail(`f did not fork the lecture: ${await f.evaluate(() => document.getElementById("state").textContent)}`));
const forkState = await f.evaluate(() => document.getElementById("state").textContent);
await f.keyboard.press(" ");
await f.keyboard.press("Escape");
await f.waitForFunction(() => !document.getElementById("live").hidden && document.getElementById("fork").hidden,
  null, { timeout: 10000 }).catch(async () => fail("Esc did not return to the live view"));
// The live page on a phone: the lecturer's screen at a readable size, scrolling sideways.
const phone = await browser.newPage({ viewport: { width: 400, height: 800 } });
await phone.goto(address);
await phone.waitForFunction(() => /\bt \d+\.\d+\//.test(document.getElementById("player").textContent),
  null, { timeout: 30000 }).catch(async () => fail("the live page on a phone showed no lecture"));
const livePx = await phone.evaluate(() => parseFloat(getComputedStyle(document.querySelector("#player .ap-term")).fontSize));
if (!(livePx >= 10)) await fail(`at 400x800 the live page's text is ${livePx} px`);
console.log(`check_web: at 400x800 the live page's text is ${livePx} px (it scrolls sideways)`);
serving.kill();
if (fErrors.length) await fail(`served page errors: ${fErrors.join("; ")}`);
console.log(`check_web: f forks a served lecture into the page (${forkState.split(":")[0]}); Esc returns to the live view`);

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

for (const v of [a, r, b, l, c]) {
  if (v.errors.length) await fail(`page errors: ${v.errors.join("; ")}`);
  if (v.outside.length) await fail(`requests outside the site: ${v.outside.join(", ")}`);
}
const size = fs.statSync(path.join(dir, "rattleback.wasm")).size;
console.log(`check_web: module ${(size / 1024).toFixed(0)} KB; first screen ${a.first} ms on loopback; no page error, no outside request`);
await browser.close();
server.close();
