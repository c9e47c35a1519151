// One player on the page (headless Chromium) playing Asteroids over a link with latency, for
// bench/page_hits.sh: turns towards the nearest target as the page draws it (a rock, or another
// ship), holds fire, and after SECONDS prints what the page counted, one line:
//   page hits: claimed N confirmed M shots S
// claimed: hits the page saw (its own bullet touching a target as drawn, flashed white at once:
// web/page/src/claims.ts); confirmed: the server's verdicts naming this player (hit markers).
//   node page_hits.mjs URL SECONDS     CHROMIUM and NODE_PATH (puppeteer-core) in the environment
import { createRequire } from 'node:module';
import { join } from 'node:path';
import { fireAtNearest } from '../web/page/test/aim.mjs';

const [url, seconds] = process.argv.slice(2);
if (!url || !seconds || !process.env.CHROMIUM || !process.env.NODE_PATH) {
  console.error('usage: CHROMIUM=... NODE_PATH=... node page_hits.mjs URL SECONDS');
  process.exit(2);
}
const puppeteer = createRequire(join(process.env.NODE_PATH, 'page-hits.cjs'))('puppeteer-core');
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

const browser = await puppeteer.launch({ executablePath: process.env.CHROMIUM, headless: true, args: ['--no-sandbox', '--disable-gpu'] });
try {
  const page = await browser.newPage();
  await page.setViewport({ width: 800, height: 600 });
  const problems = [];
  page.on('pageerror', (e) => problems.push(e.message));
  await page.goto(`${url}?name=person`);
  for (const end = Date.now() + 15000; ; await sleep(100)) {
    if (await page.evaluate(() => window.arenaPage?.snapshots > 2 && window.arenaPage.playerId > 0)) break;
    if (Date.now() > end) throw new Error(`the page did not join: ${problems.join('; ')}`);
  }
  // Rocks (2) and other ships (1), as a person would shoot them.
  await fireAtNearest(page, [2, 1], Number(seconds) * 1000);
  await sleep(1000); // the last verdicts' round trip
  const seen = await page.evaluate(() => ({
    claimed: window.arenaPage.hitsClaimed,
    confirmed: window.arenaPage.hitsConfirmed,
    shots: window.arenaPage.client.players.get(window.arenaPage.playerId)?.shots ?? 0,
  }));
  if (problems.length > 0) throw new Error(`the page failed: ${problems.join('; ')}`);
  console.log(`page hits: claimed ${seen.claimed} confirmed ${seen.confirmed} shots ${seen.shots}`);
} finally {
  await browser.close();
}
