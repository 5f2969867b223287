// A lecture followed live in headless Chromium (issue 71), as a hall would: `rattleback serve`
// on a session file that does not exist yet, a page opened before the lecture starts, a student's
// `rattleback follow` in tmux, then the lecturer's own explorer recording in tmux at 80x24,
// driven by keys. At each pause and step the page must show the lecturer's status bar (read
// from tmux) within 1 s, and the follower its fields (its own replay fields in place of the
// lecturer's speed); the three screens are saved as text beside the screenshots; a page opened late
// must show the current screen at once; when the lecturer quits, both pages must say the
// lecture ended and play it back with its chapter. Screenshots go to OUT/. No shell: every
// program is started with an argument list. Used by .ci/run:
//   node scripts/check_live.mjs target/release/rattleback OUT_DIR
import { chromium } from "playwright-core";
import { spawn, execFileSync } from "node:child_process";
import fs from "node:fs";
import path from "node:path";

const [bin, out] = process.argv.slice(2);
const rattleback = path.resolve(bin);
fs.mkdirSync(out, { recursive: true });
const session = path.join(out, "lecture.jsonl");
fs.rmSync(session, { force: true });
const tmuxName = `rattleback-live-${process.pid}`;
const followName = `rattleback-follow-${process.pid}`;
const tmux = (...args) =>
  execFileSync("tmux", args, { encoding: "utf8", stdio: ["ignore", "pipe", "ignore"] });
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

const server = spawn(rattleback, ["serve", session], { stdio: ["ignore", "pipe", "inherit"] });
let browser;
const cleanup = async () => {
  try { tmux("kill-session", "-t", tmuxName); } catch {}
  try { tmux("kill-session", "-t", followName); } catch {}
  server.kill("SIGTERM");
  if (browser) await browser.close();
};
const fail = async (message) => {
  console.error(`check_live: ${message}`);
  await cleanup();
  process.exit(1);
};
const url = await new Promise((resolve, reject) => {
  let text = "";
  server.stdout.on("data", (d) => {
    text += d;
    const nl = text.indexOf("\n");
    if (nl >= 0) resolve(text.slice(0, nl));
  });
  server.on("exit", (code) => reject(new Error(`serve exited ${code}`)));
  setTimeout(() => reject(new Error("serve printed no address in 10 s")), 10000);
}).catch((e) => fail(String(e)));
if (!/^http:\/\/127\.0\.0\.1:\d+\/$/.test(url)) await fail(`the first line is not the address: ${url}`);

browser = await chromium.launch({
  executablePath: process.env.CHROMIUM || "/usr/bin/chromium",
  args: ["--no-sandbox", "--disable-gpu", "--disable-background-networking", "--disable-component-update", "--disable-sync"],
});
const errors = [];
const open = async () => {
  const page = await browser.newPage({ viewport: { width: 1200, height: 900 } });
  page.on("pageerror", (e) => errors.push(String(e)));
  page.on("requestfailed", (r) => {
    if (!r.url().startsWith(url)) errors.push(`an outside request: ${r.url()}`);
  });
  page.on("request", (r) => {
    if (!r.url().startsWith(url) && !r.url().startsWith("data:")) errors.push(`an outside request: ${r.url()}`);
  });
  await page.goto(url);
  return page;
};
const screen = (page) =>
  page.evaluate(() =>
    [...document.querySelectorAll(".ap-term-text .ap-line, .ap-terminal .ap-line")].map((l) => l.textContent),
  );
// The status bar from its time on ("t 2.01/30 │ paused │ ×1 │ reversals 0 limit 0 │ ...").
const statusOf = (lines) => {
  for (const line of lines) {
    const m = line.match(/│ (t \d+\.\d+\/\d+ .*)$/);
    if (m) return m[1].trimEnd();
  }
  return null;
};
const lecturer = () => statusOf(tmux("capture-pane", "-p", "-t", tmuxName).split("\n"));
const latencies = [];
let shot = 0;
// The follower shows the lecturer's fields but the speed (its own replay fields instead).
const follows = async (want, what) => {
  const fields = want.split(" │ ").filter((f) => !f.startsWith("×"));
  const start = Date.now();
  let got = null;
  while (Date.now() - start < 1000) {
    const line = tmux("capture-pane", "-p", "-t", followName).split("\n").find((l) => /^ t \d/.test(l));
    got = line ? line.trim().split(" │ ") : [];
    if (fields.every((f) => got.includes(f))) return;
    await sleep(25);
  }
  await fail(`${what}: the follower shows\n  ${got.join(" │ ")}\nnot the lecturer's fields\n  ${fields.join(" │ ")}`);
};
// The page shows the lecturer's status bar within 1 s.
const same = async (page, what) => {
  await sleep(150); // the lecturer's own frame after the key
  const want = lecturer();
  if (!want) await fail(`${what}: no status bar in the lecturer's terminal`);
  const start = Date.now();
  let got = null;
  while (Date.now() - start < 1000) {
    got = statusOf(await screen(page));
    if (got === want) {
      latencies.push(Date.now() - start);
      await follows(want, what);
      shot += 1;
      for (const [name, who] of [["lecturer", tmuxName], ["follower", followName]]) {
        fs.writeFileSync(path.join(out, `pause-${shot}-${name}.txt`), tmux("capture-pane", "-p", "-t", who));
      }
      fs.writeFileSync(path.join(out, `pause-${shot}-page.txt`), (await screen(page)).join("\n") + "\n");
      return want;
    }
    await sleep(25);
  }
  await fail(`${what}: the page shows\n  ${got}\nnot the lecturer's\n  ${want}`);
};

// A parameter changed (issue 82, L3): the keys are sent, then the lecturer's terminal and the
// page are read side by side for 2 s; the lag is from the moment the lecturer first shows its
// final status bar to the moment the page first shows the same (as the lecturer's review
// measured it), and must stay under 1 s here (the measured figures are in docs/guide.md).
const changeLags = [];
const changed = async (page, keys, what) => {
  for (const k of keys) tmux("send-keys", "-t", tmuxName, k);
  const start = Date.now();
  const seen = [];
  while (Date.now() - start < 2000) {
    seen.push([Date.now(), lecturer(), statusOf(await screen(page))]);
    await sleep(5);
  }
  const want = seen[seen.length - 1][1];
  const lecAt = seen.find(([, l]) => l === want)[0];
  const pageAt = (seen.find(([, , p]) => p === want) || [null])[0];
  if (pageAt === null) await fail(`${what}: the page never showed the lecturer's\n  ${want}`);
  const lag = Math.max(0, pageAt - lecAt);
  if (lag > 1000) await fail(`${what}: the page showed the lecturer's status bar ${lag} ms after it`);
  changeLags.push(lag);
  await follows(want, what);
  return want;
};

// Opened before the lecture: it waits, saying so.
const early = await open();
await early.waitForFunction(
  () => document.body.innerText.includes("waiting for the lecturer") ||
    [...document.querySelectorAll(".ap-line")].some((l) => l.textContent.includes("waiting for the lecturer")),
  null,
  { timeout: 10000 },
).catch(() => fail("the page opened before the lecture does not say it waits"));
await early.screenshot({ path: path.join(out, "live-0-waiting.png") });

// A student's follower, started first (it waits for the file), then the lecturer.
tmux("new-session", "-d", "-s", followName, "-x", "80", "-y", "24", rattleback, "follow", session);
tmux("new-session", "-d", "-s", tmuxName, "-x", "80", "-y", "24", rattleback, "--record", session, "--preset", "subcritical");
// The lecture starts paused at t 0.
let waited = 0;
while (!lecturer() && waited < 10000) { await sleep(100); waited += 100; }
await same(early, "the start");
const key = async (k, ms) => { tmux("send-keys", "-t", tmuxName, k); if (ms) await sleep(ms); };
await key("Space", 1500);
await key("Space");
await same(early, "a pause");
await early.screenshot({ path: path.join(out, "live-1-pause.png") });
await key(".");
await same(early, "a step");
await key(".");
await same(early, "a second step");
// alpha_dot is the eighth row: three changes, each restarting the run at t 0.
for (let i = 0; i < 7; i += 1) await key("j", 60);
await sleep(300);
for (let i = 0; i < 3; i += 1) await changed(early, ["l"], `parameter change ${i + 1}`);
// A chapter, named as a lecturer types it (m: a chapter; n: a note).
await key("m", 300);
tmux("send-keys", "-t", tmuxName, "-l", "chapter one");
await key("Enter", 300);
await key("+", 100);
await key("+", 100);
await key("Space", 2000);
await key("Space");
const paused = await same(early, "a pause at x4");
// Opened late: the current screen at once.
const late = await open();
await same(late, "a page opened late");
await late.screenshot({ path: path.join(out, "live-2-late.png") });
await key("Space", 1500);
await key("Space");
await same(early, "the last pause");
await same(late, "the last pause (late page)");
const last = lecturer();
await early.screenshot({ path: path.join(out, "live-3-last-pause.png") });
// The lecturer quits: both pages say the lecture ended and play it back with its chapter.
await key("q");
for (const [page, name] of [[early, "early"], [late, "late"]]) {
  await page
    .waitForFunction(
      () => (document.getElementById("state") || {}).textContent?.includes("has ended") && window.rattlebackPlayer,
      null,
      { timeout: 20000 },
    )
    .catch(() => fail(`the ${name} page does not say the lecture ended`));
  await page.waitForTimeout(1500);
  const poster = statusOf(await screen(page));
  if (poster !== last) await fail(`the ${name} page's end shows\n  ${poster}\nnot the lecturer's last\n  ${last}`);
  const chapters = await page.evaluate(() => [...document.querySelectorAll("#chapters a")].map((a) => a.textContent));
  if (!chapters.includes("chapter one")) await fail(`the ${name} page lists no chapter "chapter one": ${chapters}`);
  await page.screenshot({ path: path.join(out, `live-4-ended-${name}.png`) });
}
// The chapter plays from its marker.
await early.click("#chapters li:nth-child(1) a");
await early.waitForTimeout(500);
const t = await early.evaluate(async () => await window.rattlebackPlayer.getCurrentTime());
if (!(t > 0)) await fail(`the chapter link did not play (${t} s)`);
if (errors.length > 0) await fail(`page errors: ${errors.join("; ")}`);
console.log(
  `check_live: ${latencies.length} pauses and steps shown within 1 s (slowest ${Math.max(...latencies)} ms after the lecturer's frame); ` +
    `${changeLags.length} parameter changes ${changeLags.join(", ")} ms behind the lecturer's screen; last: ${paused} … ${last}`,
);
await cleanup();
