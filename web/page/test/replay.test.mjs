// The replay page (/replay) in a real browser (Debian's chromium, headless, npm's
// puppeteer-core), served by a real arena-server: it plays the golden recording
// (tests/data/golden_asteroids.arpl, from a file server of this test through ?src=) to its
// end with every recorded hash verified and the final hash arena-replay computes natively,
// scrubs back and forward to the same hash; plays the server's own --record file from
// /recording on the metrics port (--serve-recording) while the server is still writing it; and opens a local file whose recorded hash
// was changed, stopping at that tick with both hashes shown. A soccer match (the SDK's build-time
// fixture, web/sdk/fixtures/record_soccer.cpp) shows the replayed game beside the world: the
// scoreboard with soccer's columns and the values arena-replay computes natively, the teams'
// goals, the events as the manifest words them and the result; a scrub back rebuilds them.
//   ARENA_SERVER  arena-server     ARENA_REPLAY  arena-replay    ARENA_CHROMIUM  the browser
//   ARENA_SOURCE_DIR  the repository (tests/data)   ARENA_SDK_FIXTURES  the SDK's fixtures
//   NODE_PATH  the page's node_modules
import { execFileSync, spawn } from 'node:child_process';
import { createHash } from 'node:crypto';
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { createServer } from 'node:http';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import { withChangedHash } from '../../sdk/test/recording_edits.mjs';
import { need, puppeteer, until } from './browser.mjs';

const server = need('ARENA_SERVER');
const replayBinary = need('ARENA_REPLAY');
const chromium = need('ARENA_CHROMIUM');
const golden = join(need('ARENA_SOURCE_DIR'), 'tests/data/golden_asteroids.arpl');
const soccer = join(need('ARENA_SDK_FIXTURES'), 'soccer.arpl');
const wait = (what, check, timeoutMs = 20000) => until(what, check, timeoutMs);

const dir = mkdtempSync(join(tmpdir(), 'arena-replay-page-'));
const servers = [];
let browser;
let files; // serves the golden recording and the soccer match to the page, from another origin
let filesUrl;
let soccerUrl;

// An arena-server with --http-port; its page's URL. With --metrics-port among `extra`, the
// metrics port's URL is in metricsUrls[page URL].
const metricsUrls = {};
async function startServer(extra) {
  const proc = spawn(server, ['--port', '0', '--http-port', '0', '--drain-grace', '0', ...extra], { stdio: ['ignore', 'pipe', 'pipe'] });
  servers.push(proc);
  let out = '';
  let err = '';
  proc.stdout.on('data', (d) => (out += d));
  proc.stderr.on('data', (d) => (err += d));
  const port = await wait('the server\'s http port', () => out.match(/^http listening on .*:(\d+)$/m)?.[1]).catch((e) => {
    throw new Error(`${e.message}\n${out}\n${err}`);
  });
  const url = `http://127.0.0.1:${port}/`;
  if (extra.includes('--metrics-port')) {
    const metrics = await wait('the server\'s metrics port', () => err.match(/metrics on (http:\/\/[^/]+\/)metrics/)?.[1]);
    metricsUrls[url] = metrics;
  }
  return url;
}

before(async () => {
  const served = { '/golden_asteroids.arpl': golden, '/soccer.arpl': soccer };
  files = createServer((request, response) => {
    const file = served[request.url];
    if (!file) {
      response.writeHead(404).end();
      return;
    }
    response.writeHead(200, { 'Content-Type': 'application/octet-stream', 'Access-Control-Allow-Origin': '*' });
    response.end(readFileSync(file));
  });
  await new Promise((resolve) => files.listen(0, '127.0.0.1', resolve));
  filesUrl = `http://127.0.0.1:${files.address().port}/golden_asteroids.arpl`;
  soccerUrl = `http://127.0.0.1:${files.address().port}/soccer.arpl`;
  browser = await puppeteer.launch({ executablePath: chromium, headless: true, args: ['--no-sandbox', '--disable-gpu'] });
});

after(async () => {
  await browser?.close();
  files?.close();
  for (const proc of servers) if (proc.exitCode === null) proc.kill('SIGKILL');
  rmSync(dir, { recursive: true, force: true });
});

async function openReplay(url) {
  const page = await browser.newPage();
  await page.setViewport({ width: 800, height: 600 });
  const problems = [];
  page.on('pageerror', (e) => problems.push(e.message));
  page.on('console', (m) => m.type() === 'error' && problems.push(m.text()));
  await page.goto(url);
  await wait('the recording loaded', () => page.evaluate(() => window.arenaReplay?.loaded || window.arenaReplay?.error)).catch((e) => {
    throw new Error(`${e.message}: ${problems.join('; ')}`);
  });
  return { page, problems };
}

const figures = (page) => page.evaluate(() => ({ ...window.arenaReplay, text: document.getElementById('hashes').textContent }));
const canvasHash = (page) => page.evaluate(() => document.getElementById('game').toDataURL()).then((d) => createHash('sha256').update(d).digest('hex'));
// What a viewer does with the scrub bar: drags it to a tick.
const scrubTo = (page, tick) => page.evaluate((t) => {
  const scrub = document.getElementById('scrub');
  scrub.value = String(t);
  scrub.dispatchEvent(new Event('input'));
}, tick);

test('the replay page plays the golden recording to its final hash, and a scrub back and forward reaches it again', { timeout: 90000 }, async () => {
  const nativeFinal = /final_hash=([0-9a-f]{16})/.exec(execFileSync(replayBinary, [golden], { encoding: 'utf8' }))[1];
  const url = await startServer([]);
  const html = await (await fetch(`${url}replay`)).text();
  assert.match(html, /id="scrub"/, 'the server serves the replay page at /replay');

  const { page, problems } = await openReplay(`${url}replay?src=${encodeURIComponent(filesUrl)}`);
  const start = await figures(page);
  assert.equal(start.error, '');
  assert.equal(start.tick, start.startTick);
  assert.ok(start.endTick > start.startTick + 100, `ticks ${start.startTick}..${start.endTick}`);
  assert.match(start.text, new RegExp(`^hashes verified: 1/${start.hashesTotal}`));
  // A sandbox recording: its rules keep no score and declare nothing, so no game panel.
  assert.equal(start.game, '');
  assert.equal(start.gamePage, '', 'no page module for the sandbox');
  assert.equal(await page.$eval('#hud', (e) => e.hidden), true, 'no scoreboard for the sandbox');
  const startCanvas = await canvasHash(page);

  await page.select('#speed', '8');
  await page.click('#play');
  await wait('a tick while playing', async () => (await figures(page)).tick > start.startTick);
  const midway = await figures(page);
  assert.ok(midway.playing || midway.tick === midway.endTick, 'it plays');
  const ended = await wait('the end of the recording', async () => {
    const f = await figures(page);
    return f.tick === f.endTick || f.error ? f : null;
  }, 60000);
  console.log(`played ${ended.endTick - ended.startTick} ticks at 8x: ${ended.text}`);
  assert.equal(ended.error, '');
  assert.equal(ended.playing, false, 'it stops at the end');
  assert.equal(ended.hashesChecked, ended.hashesTotal);
  assert.equal(ended.hash, nativeFinal, 'the final hash is the one arena-replay computes natively');
  assert.equal(ended.recordedHash, nativeFinal, 'and the recording\'s own');
  assert.match(ended.text, new RegExp(`^hashes verified: ${ended.hashesTotal}/${ended.hashesTotal} .*final hash verified`));
  assert.notEqual(await canvasHash(page), startCanvas, 'the bodies moved on the canvas');

  // Back to the middle (a re-simulation from the start), then forward to the end again.
  const middle = Math.floor((ended.startTick + ended.endTick) / 2);
  await scrubTo(page, middle);
  const back = await figures(page);
  assert.equal(back.tick, middle);
  assert.equal(back.error, '');
  assert.ok(back.hashesChecked < back.hashesTotal, `${back.hashesChecked} hashes checked up to the middle`);
  await scrubTo(page, ended.endTick);
  const again = await figures(page);
  assert.equal(again.tick, ended.endTick);
  assert.equal(again.hash, nativeFinal);
  assert.equal(again.hashesChecked, again.hashesTotal);
  assert.match(again.text, /final hash verified/);
  if (process.env.ARENA_REPLAY_SCREENSHOT) await page.screenshot({ path: process.env.ARENA_REPLAY_SCREENSHOT });
  assert.deepEqual(problems, [], 'no errors in the page');
});

test('the replay page plays the server\'s own recording from /recording on the metrics port while it is being written', { timeout: 60000 }, async () => {
  const bare = await startServer([]);
  const missing = await fetch(`${bare}recording`);
  assert.equal(missing.status, 404, 'no --record, no /recording');
  assert.match(await missing.text(), /--record/);

  const recordingFlags = ['--record', join(dir, 'live.arpl'), '--tick-rate', '60', '--hash-interval', '10'];
  const unserved = await startServer(recordingFlags);
  assert.equal((await fetch(`${unserved}recording`)).status, 404, 'without --serve-recording, no /recording');
  // While the match runs, the recording (a map of every body) is served on the metrics port only.
  const url = await startServer([...recordingFlags, '--serve-recording', '--metrics-port', '0']);
  assert.equal((await fetch(`${url}recording`)).status, 404, 'not on the public port while the match runs');
  const recording = `${metricsUrls[url]}recording`;
  // The recorder flushes once a second (every 60 ticks here): the file grows twice, so it holds
  // at least one whole second of ticks after its header.
  const size = async () => (await (await fetch(recording)).arrayBuffer()).byteLength;
  let last = await size();
  for (let grown = 0; grown < 2; ++grown) {
    const before = last;
    last = await wait('the recording to grow', async () => {
      const now = await size();
      return now > before ? now : 0;
    });
  }
  const { page, problems } = await openReplay(`${url}replay?src=${encodeURIComponent(recording)}`);
  const opened = await figures(page);
  assert.equal(opened.error, '');
  assert.match(opened.cutShort, /\S/, 'a recording still being written has no End yet');
  assert.ok(opened.endTick >= opened.startTick + 60, `ticks ${opened.startTick}..${opened.endTick}`);
  await scrubTo(page, opened.endTick);
  const played = await figures(page);
  console.log(`the server's recording so far, ${played.endTick - played.startTick} ticks: ${played.text}`);
  assert.equal(played.tick, played.endTick);
  assert.equal(played.error, '');
  assert.ok(played.hashesChecked > 5 && played.hashesChecked === played.hashesTotal, `${played.hashesChecked}/${played.hashesTotal}`);
  assert.match(played.text, /cut short here/);
  assert.deepEqual(problems, [], 'no errors in the page');
});

test('a local file with a changed recorded hash stops at that tick, both hashes on the page', { timeout: 60000 }, async () => {
  const dump = execFileSync(replayBinary, ['--dump-hashes', golden], { encoding: 'utf8' });
  const hashes = dump.trimEnd().split('\n').slice(1).map((line) => {
    const [tick, hash] = line.split(',');
    return { tick: Number(tick), hash };
  });
  const changed = withChangedHash(new Uint8Array(readFileSync(golden)), hashes);
  const file = join(dir, 'changed.arpl');
  writeFileSync(file, changed.bytes);

  const url = await startServer([]);
  const page = await browser.newPage();
  await page.setViewport({ width: 800, height: 600 });
  const problems = [];
  page.on('pageerror', (e) => problems.push(e.message));
  await page.goto(`${url}replay`);
  await wait('the page ready', () => page.evaluate(() => window.arenaReplay !== undefined));
  await (await page.$('#file')).uploadFile(file);
  await wait('the file loaded', () => page.evaluate(() => window.arenaReplay.loaded));
  assert.equal((await figures(page)).source, 'changed.arpl');
  await page.select('#speed', '8');
  await page.click('#play');
  const stopped = await wait('the mismatch', async () => {
    const f = await figures(page);
    return f.error ? f : null;
  }, 30000);
  const wrong = (BigInt('0x' + changed.recorded) ^ 1n).toString(16).padStart(16, '0');
  console.log(`a changed hash: ${stopped.text}`);
  assert.equal(stopped.tick, changed.tick);
  assert.equal(stopped.playing, false);
  assert.equal(await page.$eval('#hashes', (e) => e.className), 'failed');
  assert.match(stopped.text, new RegExp(`hash MISMATCH at tick ${changed.tick}: the recording has ${wrong}, this replay computed ${changed.recorded}`));
  assert.match(stopped.text, new RegExp(`^hashes verified: 1/${stopped.hashesTotal}`));
  assert.deepEqual(problems, [], 'no errors in the page');
});

// What the game panel shows: the scoreboard's head and rows, the teams (name: first value), the
// event log (newest first, with each entry's tick and kind) and the result line.
const panel = (page) => page.evaluate(() => ({
  hidden: document.getElementById('hud').hidden,
  head: [...document.querySelectorAll('#scoreboard-head th')].map((t) => t.textContent),
  rows: [...document.querySelectorAll('#scoreboard tr')].map((tr) => [...tr.children].map((td) => td.textContent)),
  teams: Object.fromEntries([...document.querySelectorAll('#teams span')].map((s) => [s.dataset.team, Number(s.dataset.value)])),
  events: [...document.querySelectorAll('#events li')].map((li) => ({ tick: Number(li.dataset.tick), kind: li.dataset.kind, text: li.textContent })),
  result: document.getElementById('result').hidden ? '' : document.getElementById('result').textContent,
}));
// The rows the page should show from arena-replay's scoreboard at `until`: soccer's columns
// (team by name, goals, kicks), ranked by goals, then by player id.
function expectedRows(until) {
  const board = JSON.parse(execFileSync(replayBinary, ['--scoreboard', '--until', String(until), soccer], { encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'] }));
  return board
    .sort((a, b) => b.goals - a.goals || a.player - b.player)
    .slice(0, 10)
    .map((l) => [l.name || `player ${l.player}`, ['', 'red', 'blue'][l.team], String(l.goals), String(l.kicks)]);
}

test('a replayed soccer match shows its scoreboard, teams, events and result, and a scrub back rebuilds them', { timeout: 90000 }, async () => {
  const url = await startServer([]);
  const { page, problems } = await openReplay(`${url}replay?src=${encodeURIComponent(soccerUrl)}`);
  const start = await figures(page);
  assert.equal(start.error, '');
  assert.equal(start.game, 'soccer');
  assert.equal(start.gamePage, 'soccer', 'soccer\'s page module draws its pitch under the replay too');
  const opened = await panel(page);
  assert.equal(opened.hidden, false);
  assert.deepEqual(opened.head, ['player', 'Team', 'Goals', 'Kicks'], 'soccer\'s columns, from its manifest');
  assert.deepEqual(opened.rows, [], 'nobody has joined at the start');
  assert.deepEqual(opened.events, []);
  assert.equal(opened.result, '');

  // Played at 8x, the log fills as the replay reaches each event.
  await page.select('#speed', '8');
  await page.click('#play');
  const told = await wait('an event in the log while playing', async () => {
    const p = await panel(page);
    return p.events.length > 0 ? p : null;
  }, 30000);
  await page.click('#play'); // pause
  console.log(`while playing: ${told.events[0].text}`);
  assert.ok((await figures(page)).tick >= told.events[0].tick);

  // The end: the values the recording reached, every event told, the result.
  const end = start.endTick;
  await scrubTo(page, end);
  const last = await panel(page);
  const state = await figures(page);
  console.log(`at the end: ${JSON.stringify(last.rows)} ${JSON.stringify(last.teams)}; ${last.result}; ${last.events.map((e) => e.text).join(' | ')}`);
  assert.deepEqual(last.rows, expectedRows(end), 'the scoreboard arena-replay computes natively');
  assert.ok(last.rows.some((r) => Number(r[3]) > 0), 'kicks counted');
  assert.ok(last.events.length > 0);
  for (const e of last.events) assert.match(e.text, /^\d+:\d\d [^{}]+$/, 'each message with its values in place');
  assert.deepEqual(last.events.map((e) => e.tick), [...last.events.map((e) => e.tick)].sort((a, b) => b - a), 'newest first');
  assert.deepEqual(last.events.map((e) => e.text.replace(/^\d+:\d\d /, '')), state.events.slice(-10).reverse().map((e) => e.text), 'the newest ten');
  // Every goal is told, for the team whose goals show on the team line; scorers by their recorded names.
  const goals = state.events.filter((e) => e.name === 'goal' || e.name === 'own_goal');
  assert.ok(goals.length > 0, 'the fixture has a goal');
  for (const g of goals) assert.match(g.text, /^(own goal by )?(ana|bo|cy|di|ed|flo)\b/, g.text);
  const counted = { red: goals.filter((g) => g.values[1] === 1).length, blue: goals.filter((g) => g.values[1] === 2).length };
  assert.deepEqual(last.teams, counted, 'the team line: the goals the events told');
  const winner = counted.red === counted.blue ? 'a draw' : counted.red > counted.blue ? 'red win' : 'blue win';
  assert.equal(last.result, `match over: ${winner}`);
  assert.match(last.events[0].text, new RegExp(`full time: ${counted.red === counted.blue ? 'a draw' : counted.red > counted.blue ? 'red' : 'blue'}$`));

  // Back to just before the first event: an empty log, no result, the scoreboard of then.
  const first = state.events[0];
  await scrubTo(page, first.tick - 1);
  const before = await panel(page);
  assert.deepEqual(before.events, []);
  assert.equal(before.result, '');
  assert.deepEqual(before.rows, expectedRows(first.tick - 1));
  // The middle: the events up to it, and forward to the end: all of them again.
  const middle = Math.floor((start.startTick + end) / 2);
  await scrubTo(page, middle);
  const half = await panel(page);
  assert.deepEqual(half.events, last.events.filter((e) => e.tick <= middle));
  assert.deepEqual(half.rows, expectedRows(middle));
  await scrubTo(page, end);
  assert.deepEqual(await panel(page), last, 'the same panel at the end again');
  if (process.env.ARENA_REPLAY_SOCCER_SCREENSHOT) await page.screenshot({ path: process.env.ARENA_REPLAY_SOCCER_SCREENSHOT });
  assert.deepEqual(problems, [], 'no errors in the page');
});
