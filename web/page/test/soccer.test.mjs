// The page plays a game it has no code for, from the manifest in the Welcome: a real
// arena-server playing soccer (--mode soccer), a real headless Chromium. The scoreboard's
// columns are soccer's, the teams show with their scores, the keys are the ones soccer declares
// (Space kicks), and a player who runs at the ball and kicks scores: the goal is told as the
// manifest words it, and the HUD's team score and the server's agree. Soccer's page module
// (games/soccer/page.ts) draws the pitch's markings where the pitch is; tag, which has no page
// module, draws from its manifest alone, as every game did before page modules.
//   ARENA_SERVER  ARENA_CHROMIUM  NODE_PATH (see page.test.mjs)
import { mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import { launchBrowser, need, startServer, until } from './browser.mjs';

const server = need('ARENA_SERVER');
const chromium = need('ARENA_CHROMIUM');

const dir = mkdtempSync(join(tmpdir(), 'arena-soccer-page-'));
const statsFile = join(dir, 'stats.json');
let proc;
let exited;
let browser;
let url;

before(async () => {
  ({ proc, exited, url } = await startServer(server, ['--port', '0', '--http-port', '0', '--mode', 'soccer', '--stats-json', statsFile,
    '--drain-grace', '1']));
  browser = await launchBrowser(chromium);
});

after(async () => {
  await browser?.close();
  if (proc && proc.exitCode === null) proc.kill('SIGKILL');
  rmSync(dir, { recursive: true, force: true });
});

// Soccer's pitch (games/soccer/soccer_pitch.hpp), m: the goal lines, the touchlines, the goals'
// mouths. The module finds them in the walls of the Welcome's world config.
const PITCH = { left: 4, right: 44, bottom: 4, top: 24, goalLow: 11, goalHigh: 17 };

// The canvas's colour at world points, for a spectator's camera (the whole world, centred on its
// middle): each point's brightest pixel within 2 px (a line 2 px wide may fall between pixels)
// and its own pixel.
function colours(page, points) {
  return page.evaluate((points) => {
    const canvas = document.getElementById('game');
    const g = canvas.getContext('2d');
    const { width, height } = window.arenaPage.client.session.world;
    const scale = Math.min(canvas.width, canvas.height) / Math.max(width, height);
    return points.map(([x, y]) => {
      const sx = Math.round(canvas.width / 2 + (x - width / 2) * scale);
      const sy = Math.round(canvas.height / 2 - (y - height / 2) * scale);
      const d = g.getImageData(sx - 2, sy - 2, 5, 5).data;
      let brightest = [0, 0, 0];
      for (let i = 0; i < d.length; i += 4) {
        if (d[i] + d[i + 1] + d[i + 2] > brightest[0] + brightest[1] + brightest[2]) brightest = [d[i], d[i + 1], d[i + 2]];
      }
      const at = 4 * (2 * 5 + 2);
      return { brightest, own: [d[at], d[at + 1], d[at + 2]] };
    });
  }, points);
}

test('soccer\'s page module draws the pitch: the surface, the halfway line, the centre circle, the goal areas', { timeout: 30000 }, async () => {
  const page = await browser.newPage();
  await page.setViewport({ width: 800, height: 600 });
  const problems = [];
  page.on('pageerror', (e) => problems.push(e.message));
  page.on('console', (m) => m.type() === 'error' && problems.push(m.text()));
  await page.goto(`${url}?spectate`);
  await until('the pitch drawn a few times', () => page.evaluate(() => window.arenaPage?.snapshots > 2 && window.arenaPage.gamePageFrames > 5))
    .catch((e) => {
      throw new Error(`${e.message}: ${problems.join('; ')}`);
    });
  assert.equal(await page.evaluate(() => window.arenaPage.gamePage), 'soccer', 'the module of the manifest\'s game');
  const frames = await page.evaluate(() => window.arenaPage.gamePageFrames);
  await until('more frames drawn by the module', () => page.evaluate((f) => window.arenaPage.gamePageFrames > f + 5, frames));

  const p = PITCH;
  const midX = (p.left + p.right) / 2;
  const midY = (p.bottom + p.top) / 2;
  const radius = (p.top - p.bottom) / 5;  // page.ts: a fifth of the pitch's width
  const half = (p.goalHigh - p.goalLow) / 2;  // a goal area: half the goal's width deep
  const lines = {
    'the halfway line near the bottom touchline': [midX, p.bottom + 2],
    'the halfway line near the top touchline': [midX, p.top - 2],
    'the centre circle, right': [midX + radius, midY],
    'the centre circle, top': [midX, midY + radius],
    'the left goal area\'s front': [p.left + half, midY - 1],
    'the left goal area\'s side': [p.left + half / 2, p.goalLow - half],
    'the right goal area\'s front': [p.right - half, midY + 1],
    'the right goal area\'s side': [p.right - half / 2, p.goalHigh + half],
  };
  const surface = { 'the left half': [p.left + 10, p.top - 3], 'the right half': [p.right - 10, p.bottom + 3] };
  const outside = { 'beside the pitch': [1, 1] };
  const [onLines, onSurface, offPitch] = await Promise.all([lines, surface, outside].map((set) => colours(page, Object.values(set))));
  const sum = (c) => c[0] + c[1] + c[2];
  Object.keys(lines).forEach((what, i) => assert.ok(sum(onLines[i].brightest) > 250, `${what}: a light line, got ${onLines[i].brightest}`));
  const green = ([r, g, b]) => g > r && g > b;
  Object.keys(surface).forEach((what, i) => {
    const c = onSurface[i].own;
    assert.ok(green(c) && sum(c) < 150, `${what}: the dark green surface, got ${c}`);
    assert.ok(sum(onSurface[i].brightest) < 150, `${what}: no line near, got ${onSurface[i].brightest}`);
  });
  assert.ok(!green(offPitch[0].own), `beside the pitch: the page's background, got ${offPitch[0].own}`);
  assert.deepEqual(problems, []);
  await page.close();
});

test('a game without a page module draws from its manifest alone, as before (tag)', { timeout: 30000 }, async () => {
  const tag = await startServer(server, ['--port', '0', '--http-port', '0', '--mode', 'tag']);
  try {
    const page = await browser.newPage();
    await page.setViewport({ width: 800, height: 600 });
    const problems = [];
    page.on('pageerror', (e) => problems.push(e.message));
    page.on('console', (m) => m.type() === 'error' && problems.push(m.text()));
    await page.goto(`${tag.url}?name=runner`);
    await until('tag drawn', () => page.evaluate(() => window.arenaPage?.snapshots > 2 && window.arenaPage.frames > 10 && window.arenaPage.drawn > 0))
      .catch((e) => {
        throw new Error(`${e.message}: ${problems.join('; ')}`);
      });
    assert.equal(await page.evaluate(() => window.arenaPage.game?.name), 'tag');
    assert.equal(await page.evaluate(() => window.arenaPage.gamePage), '', 'no module: tag has none');
    assert.equal(await page.evaluate(() => window.arenaPage.gamePageFrames), 0);
    assert.deepEqual(problems, []);
    await page.close();
  } finally {
    tag.proc.kill('SIGKILL');
  }
});

test('the page plays soccer from its manifest: two teams, a score, a kick and a goal', { timeout: 90000 }, async () => {
  const page = await browser.newPage();
  await page.setViewport({ width: 800, height: 600 });
  const problems = [];
  page.on('pageerror', (e) => problems.push(e.message));
  page.on('console', (m) => m.type() === 'error' && problems.push(m.text()));
  await page.goto(`${url}?name=striker`);
  await until('the welcome and snapshots', () => page.evaluate(() => window.arenaPage?.snapshots > 2 && window.arenaPage.playerId > 0))
    .catch((e) => {
      throw new Error(`${e.message}: ${problems.join('; ')}`);
    });

  // The manifest: soccer's name, columns, teams and keys.
  assert.equal(await page.evaluate(() => window.arenaPage.game?.name), 'soccer');
  const head = await page.$$eval('#scoreboard-table thead th', (ths) => ths.map((t) => t.textContent));
  assert.deepEqual(head, ['player', 'Team', 'Goals', 'Kicks']);
  assert.match(await page.$eval('#help', (e) => e.textContent), /Space kick/);
  const row = await until('the own scoreboard line', () => page.$$eval('#scoreboard tr.me td', (tds) => tds.map((t) => t.textContent)));
  assert.deepEqual(row, ['striker', 'red', '0', '0'], 'the first player joins red');
  const teams = () => page.$$eval('#teams span', (spans) => Object.fromEntries(spans.map((s) => [s.dataset.team, Number(s.dataset.value)])));
  assert.deepEqual(await until('the teams\' scores', async () => ((await teams()).red !== undefined ? teams() : null)), { red: 0, blue: 0 });

  // Alone on the pitch, red starts on the line through the goals facing blue's goal, the ball
  // ahead: run at it with Space held (a kick each time it is within reach) until it goes in.
  await page.keyboard.down('ArrowUp');
  await page.keyboard.down('Space');
  const goal = await until('a goal told on the page', () => page.evaluate(() => window.arenaPage.records.find((r) => r.kind === 0)), 30000)
    .catch(async (e) => {
      const own = await page.evaluate(() => JSON.stringify(window.arenaPage.view.bodies.filter((b) => b.owner !== 0)));
      throw new Error(`${e.message}: bodies ${own}; ${problems.join('; ')}`);
    });
  await page.keyboard.up('Space');
  await page.keyboard.up('ArrowUp');
  assert.equal(goal.text, 'striker scores for red');
  assert.equal((await until('red\'s score on the HUD', async () => ((await teams()).red === 1 ? teams() : null))).red, 1);
  assert.equal(await until('the own goals', () => page.$eval('#score', (e) => (e.dataset.value === '1' ? e.dataset.value : null))), '1');

  // The server agrees: its stats, written as it stops, give red the goal and the striker its goal.
  proc.kill('SIGTERM');
  const end = await exited;
  assert.equal(end.code, 0, `the server exited with ${JSON.stringify(end)}`);
  const stats = JSON.parse(readFileSync(statsFile, 'utf8'));
  assert.deepEqual(stats.teams.map((t) => [t.name, t.score]), [['red', 1], ['blue', 0]]);
  assert.equal(stats.winning_team, 1);
  assert.equal(stats.scoreboard[0].score, 1);
  assert.equal(stats.scoreboard[0].team, 1);
  assert.deepEqual(problems, []);
});
