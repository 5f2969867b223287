// Opens a page written by `rattleback replay FILE --export-html OUT` in headless Chromium
// (playwright-core driving the system's chromium), lets the player load the inlined cast, seeks
// to its end and checks that the terminal it draws holds every expected text (the session's last
// screen), that the chapters are links and markers, and that the console has no error; writes a
// screenshot. Used by .ci/run:
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
await page.evaluate(async (d) => {
  await window.rattlebackPlayer.seek(d);
}, duration);
await page.waitForTimeout(1000);
// The player draws each row as an `.ap-line` of spans (3.18; older releases used `.ap-terminal`).
const text = await page.evaluate(() =>
  [...document.querySelectorAll(".ap-term-text .ap-line, .ap-terminal .ap-line")]
    .map((l) => l.textContent)
    .join("\n"),
);
for (const want of expected) {
  if (!text.includes(want)) await fail(`the last frame lacks "${want}":\n${text}`);
}
const links = await page.evaluate(() => document.querySelectorAll("#chapters a").length);
const markers = await page.evaluate(() => document.querySelectorAll(".ap-marker-container").length);
if (errors.length > 0) await fail(`console errors: ${errors.join("; ")}`);
await page.screenshot({ path: shot, fullPage: true });
console.log(
  `check_page: ${pagePath}: duration ${duration.toFixed(1)} s, last frame has ${expected.length} expected texts, ${links} chapter link(s), ${markers} marker(s); screenshot ${shot}`
);
await browser.close();
