// Opens a page written by `rattleback replay FILE --export-html OUT` in headless Chromium
// (playwright-core driving the system's chromium) and checks, as a reader would see it: before
// any click the player shows the session's last screen (the poster) with every expected text and
// has not started; each chapter link jumps the player to its marker; the end of the cast shows
// the same screen; the console has no error. Writes a screenshot taken before any click.
// Used by .ci/run:
//   node scripts/check_page.mjs PAGE.html SHOT.png "t 30.00/30" "reversals 7 limit 7" …
import { chromium } from "playwright-core";
import path from "node:path";

const [pagePath, shot, ...expected] = process.argv.slice(2);
const executablePath = process.env.CHROMIUM || "/usr/bin/chromium";
const browser = await chromium.launch({ executablePath, args: ["--no-sandbox"] });
const fail = async (message) => {
  console.error(`check_page: ${message}`);
  await browser.close();
  process.exit(1);
};
const page = await browser.newPage({ viewport: { width: 1200, height: 1000 } });
const errors = [];
page.on("pageerror", (e) => errors.push(String(e)));
page.on("console", (m) => {
  if (m.type() === "error") errors.push(m.text());
});
await page.goto("file://" + path.resolve(pagePath));
await page.waitForFunction(() => window.rattlebackPlayer !== undefined, null, { timeout: 20000 });
const duration = await page.evaluate(async () => await window.rattlebackPlayer.getDuration());
if (!(duration > 0)) await fail(`the player has no duration (${duration})`);
// The player draws each row as an `.ap-line` of spans (3.18; older releases used `.ap-terminal`).
const screen = () =>
  page.evaluate(() =>
    [...document.querySelectorAll(".ap-term-text .ap-line, .ap-terminal .ap-line")]
      .map((l) => l.textContent)
      .join("\n"),
  );
// Before any click: the poster is the session's last frame (issue 55), not an empty box.
await page.waitForTimeout(1000);
const poster = await screen();
for (const want of expected) {
  if (!poster.includes(want)) await fail(`the poster (no click) lacks "${want}":\n${poster}`);
}
const now = () => page.evaluate(async () => await window.rattlebackPlayer.getCurrentTime());
const before = await now();
await page.waitForTimeout(500);
if ((await now()) !== before) await fail(`the page plays on its own from ${before} s`);
await page.screenshot({ path: shot, fullPage: true });
// A click plays the lecture from its beginning, not from the poster's end.
await page.click(".ap-player");
await page.waitForTimeout(400);
const started = await now();
await page.evaluate(() => window.rattlebackPlayer.pause());
if (!(started > 0 && started < 2)) await fail(`a click on the poster plays from ${started} s, not from the start`);
// Each chapter link jumps the player to its marker (the time the link shows).
const chapters = await page.evaluate(() =>
  [...document.querySelectorAll("#chapters a")].map((a) => Number(a.dataset.time)),
);
for (let i = 0; i < chapters.length; i++) {
  await page.click(`#chapters li:nth-child(${i + 1}) a`);
  await page.waitForTimeout(300);
  const now = await page.evaluate(async () => {
    const p = window.rattlebackPlayer;
    const t = await p.getCurrentTime();
    p.pause();
    return t;
  });
  if (!(now >= chapters[i] - 0.05 && now <= chapters[i] + 1.5))
    await fail(`chapter ${i + 1} jumped to ${now} s, not to its marker at ${chapters[i]} s`);
}
// And played to its end, the same last frame.
await page.evaluate(async (d) => {
  await window.rattlebackPlayer.seek(d);
}, duration);
await page.waitForTimeout(1000);
const text = await screen();
for (const want of expected) {
  if (!text.includes(want)) await fail(`the last frame lacks "${want}":\n${text}`);
}
const links = await page.evaluate(() => document.querySelectorAll("#chapters a").length);
const markers = await page.evaluate(() => document.querySelectorAll(".ap-marker-container").length);
if (errors.length > 0) await fail(`console errors: ${errors.join("; ")}`);
console.log(
  `check_page: ${pagePath}: duration ${duration.toFixed(1)} s, the poster and the last frame have ${expected.length} expected texts, ${links} chapter link(s) each jumping to its marker, ${markers} marker(s); screenshot (before any click) ${shot}`
);
await browser.close();
