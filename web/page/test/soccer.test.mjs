// The page plays a game it has no code for, from the manifest in the Welcome: a real
// arena-server playing soccer (--mode soccer), a real headless Chromium. The scoreboard's
// columns are soccer's, the teams show with their scores, the keys are the ones soccer declares
// (Space kicks), and a player who runs at the ball and kicks scores: the goal is told as the
// manifest words it, and the HUD's team score and the server's agree.
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
