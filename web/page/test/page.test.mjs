// The page in a real browser (Debian's chromium, headless, driven by npm's puppeteer-core)
// against a real arena-server playing Asteroids, started with --http-port and no --web-root:
// the build put the page in build/web, beside bin/. A second page joins as a separate client
// and watches the probe's ship in its own snapshots from the server; a third watches the match
// as a spectator (/?spectate): no ship of its own, every body drawn, counted by the server.
// On a second server, a player with ?debug=lag aims at rocks and fires: the server confirms its
// hits (hit markers, the HUD's counter) and the overlay draws the targets each shot's view held.
//   ARENA_SERVER   the arena-server binary       ARENA_CHROMIUM  the browser
//   NODE_PATH      the page's node_modules (puppeteer-core, from web/page/package-lock.json)
import { spawn } from 'node:child_process';
import { createHash } from 'node:crypto';
import { mkdtempSync, readFileSync, rmSync, statSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import { fireAtNearest } from './aim.mjs';
import { need, puppeteer, sleep, startServer, until } from './browser.mjs';

const server = need('ARENA_SERVER');
const chromium = need('ARENA_CHROMIUM');
const webDir = need('ARENA_WEB_DIR');

const dir = mkdtempSync(join(tmpdir(), 'arena-page-'));
const statsFile = join(dir, 'stats.json');
let proc;
let exited;
let browser;
let url;

before(async () => {
  const config = join(dir, 'game.json');
  writeFileSync(config, '{"preset": "asteroids", "rules": "asteroids"}');
  // --view-radius 0: the watcher sees the whole world, wherever the probe's ship is.
  proc = spawn(server, ['--port', '0', '--http-port', '0', '--config', config, '--stats-json', statsFile, '--drain-grace', '1',
    '--view-radius', '0'], { stdio: ['ignore', 'pipe', 'pipe'] });
  exited = new Promise((resolve) => proc.on('exit', (code, signal) => resolve({ code, signal })));
  let out = '';
  let err = '';
  proc.stdout.on('data', (d) => (out += d));
  proc.stderr.on('data', (d) => (err += d));
  const port = await until('the server\'s http port', () => out.match(/^http listening on .*:(\d+)$/m)?.[1]).catch((e) => {
    throw new Error(`${e.message}\n${out}\n${err}`);
  });
  url = `http://127.0.0.1:${port}/`;
  browser = await puppeteer.launch({ executablePath: chromium, headless: true, args: ['--no-sandbox', '--disable-gpu'] });
});

after(async () => {
  await browser?.close();
  if (proc && proc.exitCode === null) proc.kill('SIGKILL');
  rmSync(dir, { recursive: true, force: true });
});

async function open(name, query = '', at = url) {
  const page = await browser.newPage();
  await page.setViewport({ width: 800, height: 600 });
  const problems = [];
  page.on('pageerror', (e) => problems.push(e.message));
  page.on('console', (m) => m.type() === 'error' && problems.push(m.text()));
  await page.goto(`${at}?name=${name}${query}`);
  await until(`${name}'s welcome`, () => page.evaluate(() => window.arenaPage?.snapshots > 2 && window.arenaPage.playerId > 0)).catch((e) => {
    throw new Error(`${e.message}: ${problems.join('; ')}`);
  });
  return { page, problems };
}

const canvasHash = (page) => page.evaluate(() => document.getElementById('game').toDataURL()).then((d) => createHash('sha256').update(d).digest('hex'));

test('the page plays: joins, thrusts, fires, draws, and its HUD shows the server\'s score', { timeout: 60000 }, async () => {
  const index = await (await fetch(url)).text();
  assert.match(index, /<canvas id="game"/, 'the server serves the page at / with no --web-root');

  const { page: probe, problems } = await open('probe');
  const probeId = await probe.evaluate(() => window.arenaPage.playerId);
  assert.equal(await probe.evaluate(() => window.arenaPage.client.players.get(window.arenaPage.playerId)?.name), 'probe');

  // The canvas changes between frames (the rocks drift, the HUD's figures tick). Polled, not
  // compared once after 300 ms: on a loaded machine the headless browser sometimes drew no
  // changed frame in that time, and the test failed though the page was fine.
  const a = await canvasHash(probe);
  await until('the canvas redrawn', async () => (await canvasHash(probe)) !== a);
  if (process.env.ARENA_PAGE_SCREENSHOT) await probe.screenshot({ path: process.env.ARENA_PAGE_SCREENSHOT });

  // The watcher opens in a second tab; the probe's tab comes back to the front, where the
  // browser runs its requestAnimationFrame (and its input timer) at full rate.
  const { page: watcher } = await open('watcher');
  await probe.bringToFront();

  // Holding the up arrow moves the probe's ship, as the watcher's snapshots from the server show.
  const probeShip = () => watcher.evaluate((id) => {
    const s = window.arenaPage.view.bodies.find((b) => b.owner === id);
    return s ? { tick: window.arenaPage.view.tick, x: s.x, y: s.y } : null;
  }, probeId);
  const start = await until('the probe\'s ship in the watcher\'s view', probeShip).catch(async (e) => {
    const seen = await watcher.evaluate(() => window.arenaPage.view.bodies.map((b) => `${b.id}:${b.owner}`).join(' '));
    const own = await probe.evaluate(() => `${window.arenaPage.playerId}/${window.arenaPage.entityId}`);
    throw new Error(`${e.message}: probe ${own}, watcher sees ${seen}`);
  });
  await probe.keyboard.down('ArrowUp');
  await sleep(1500);
  await probe.keyboard.up('ArrowUp');
  const moved = await until('a later snapshot', async () => {
    const s = await probeShip();
    return s && s.tick > start.tick + 60 ? s : null;
  });
  const width = await probe.evaluate(() => window.arenaPage.client.session.world.width);
  const wrap = (d) => d - Math.round(d / width) * width;
  const distance = Math.hypot(wrap(moved.x - start.x), wrap(moved.y - start.y));
  console.log(`thrust for 1.5 s moved the probe's ship ${distance.toFixed(1)} m in the server's snapshots`);
  assert.ok(distance > 5, `the ship moved ${distance} m`);


  // Space fires: the server's count of shots rises (arena_shots_total on /metrics; the
  // scoreboard lines the clients get carry shots only along with a change of score or lives).
  const shots = async () => Number((await (await fetch(`${url}metrics`)).text()).match(/^arena_shots_total (\d+)$/m)?.[1] ?? NaN);
  const shotsBefore = await shots();
  assert.ok(Number.isFinite(shotsBefore), 'the server exports arena_shots_total');
  const predictedBefore = await probe.evaluate(() => window.arenaPage.predictedShotsDrawn);
  await probe.keyboard.down(' ');
  await probe.keyboard.down('ArrowLeft');
  await sleep(2000);
  await probe.keyboard.up(' ');
  await probe.keyboard.up('ArrowLeft');
  const shotsAfter = await until('shots counted by the server', async () => {
    const n = await shots();
    return n > shotsBefore ? n : 0;
  });
  console.log(`space held for 2 s: ${shotsAfter - shotsBefore} shots counted by the server`);
  // Each bullet was drawn as it was fired, before any snapshot held it (the SDK's prediction).
  const predictedDrawn = (await probe.evaluate(() => window.arenaPage.predictedShotsDrawn)) - predictedBefore;
  assert.ok(predictedDrawn > 0, `predicted shots drawn: ${predictedDrawn}`);

  // Aim at the nearest rock and fire, with the keys, until the HUD shows points (or 6 s pass):
  // then the comparison with the server's score below is not one of two zeros.
  const hudScore = () => probe.evaluate(() => Number(document.getElementById('score').dataset.value));
  await fireAtNearest(probe, [2], 6000, async () => (await hudScore()) !== 0);

  const figures = await probe.evaluate(() => ({
    fps: window.arenaPage.fps,
    frames: window.arenaPage.frames,
    snapshotRate: window.arenaPage.snapshotRate,
    errorMax: window.arenaPage.predictionErrorMax,
    errors: window.arenaPage.predictionErrors,
    arrival: window.arenaPage.arrivalToRender,
    hud: document.getElementById('hud').innerText,
  }));
  const pct = (xs, p) => [...xs].sort((x, y) => x - y)[Math.min(xs.length - 1, Math.floor((p / 100) * xs.length))];
  console.log(`frames per second ${figures.fps} (${figures.frames} drawn), snapshots ${figures.snapshotRate}/s`);
  console.log(`prediction error p99 ${(pct(figures.errors, 99) * 100).toFixed(1)} cm, max ${(figures.errorMax * 100).toFixed(1)} cm ` +
              `(${figures.errors.length} snapshots)`);
  console.log(`snapshot arrival to render p50 ${pct(figures.arrival, 50).toFixed(1)} ms, p99 ${pct(figures.arrival, 99).toFixed(1)} ms ` +
              `(${figures.arrival.length} snapshots)`);
  console.log(`arena_core.wasm ${statSync(join(webDir, 'arena_core.wasm')).size} bytes, page.mjs ${statSync(join(webDir, 'page.mjs')).size} bytes`);
  assert.ok(figures.fps > 0, 'requestAnimationFrame draws');
  assert.ok(figures.arrival.length > 0 && figures.errors.length > 0, 'the page measures its snapshots');
  assert.match(figures.hud, /ping \d+(\.\d+)? ms/);
  // The HUD's count of inputs left out is the SDK's: read both at once, between two HUD updates.
  const leftOut = await probe.evaluate(() => ({
    hud: Number(document.getElementById('left-out').textContent),
    sdk: window.arenaPage.client.inputsLeftOut,
  }));
  assert.ok(Number.isInteger(leftOut.hud) && leftOut.hud >= 0 && leftOut.hud <= leftOut.sdk,
            `inputs left out: the HUD says ${leftOut.hud}, the SDK ${leftOut.sdk}`);
  assert.match(figures.hud, /probe/, 'the scoreboard names the probe');

  // A spectator watches: the players' ships (and every other body) drawn, none of its own, the
  // HUD says so beside the scoreboard, its keys do nothing, and the server counts it apart.
  // Opened after the probe's figures are taken: its tab in front pauses the probe's frames.
  const metric = async (name) => Number((await (await fetch(`${url}metrics`)).text()).match(new RegExp(`^${name} (\\d+)$`, 'm'))?.[1] ?? NaN);
  const { page: eye, problems: eyeProblems } = await open('eye', '&spectate');
  const seen = await until('the players\' ships drawn on the spectator\'s page', () => eye.evaluate(() => {
    const p = window.arenaPage;
    const players = p.view.bodies.filter((b) => b.owner !== 0).length;
    return p.drawn > 0 && players > 0 ? { drawn: p.drawn, received: p.view.bodies.length, players } : null;
  }));
  const eyeState = await eye.evaluate(() => ({
    spectating: window.arenaPage.spectating && window.arenaPage.client.spectating,
    entityId: window.arenaPage.entityId,
    own: window.arenaPage.client.stateAt(performance.now()).own,
    ownBodies: window.arenaPage.view.bodies.filter((b) => b.owner === window.arenaPage.playerId).length,
    hud: document.getElementById('hud').innerText,
  }));
  console.log(`the spectator received ${seen.received} bodies (${seen.players} of the players) and drew ${seen.drawn}`);
  assert.equal(eyeState.spectating, true);
  assert.equal(eyeState.entityId, 0, 'no body of its own');
  assert.equal(eyeState.own, null, 'no own ship to draw');
  assert.equal(eyeState.ownBodies, 0);
  assert.match(eyeState.hud, /spectating/);
  await until('the probe on the spectator\'s scoreboard', () => eye.evaluate(() => /probe/.test(document.getElementById('scoreboard').innerText)));
  assert.equal(await metric('arena_spectators_connected'), 1, 'the server counts one spectator');
  assert.equal(await metric('arena_players_connected'), 2, 'and two players');
  await eye.keyboard.down('ArrowUp');
  await eye.keyboard.down(' ');
  await sleep(500);
  await eye.keyboard.up(' ');
  await eye.keyboard.up('ArrowUp');
  assert.equal(await eye.evaluate(() => window.arenaPage.bye), null, 'its keys send nothing the server refuses');
  assert.equal(await metric('arena_spectators_connected'), 1);

  // The probe's bullets still in flight may score after its HUD was last drawn (its tab has
  // been behind the spectator's): back in front, it waits until none is left in its view and
  // draws a few frames more, so the score cannot change between its HUD and the server's end.
  await probe.bringToFront();
  await until('the probe\'s bullets gone', () => probe.evaluate(() =>
    !window.arenaPage.client.stateAt(performance.now()).bodies.some((b) => b.kind === 3)));
  const framesThen = await probe.evaluate(() => window.arenaPage.frames);
  await until('frames drawn since', () => probe.evaluate((n) => window.arenaPage.frames > n + 10, framesThen));

  // The server ends the match; the HUD's score is the server's, as --stats-json has it.
  proc.kill('SIGTERM');
  const bye = await until('the Bye', () => probe.evaluate(() => window.arenaPage.bye));
  assert.match(bye.reason, /SIGTERM/);
  const eyeBye = await until('the spectator\'s Bye', () => eye.evaluate(() => window.arenaPage.bye));
  assert.match(eyeBye.reason, /SIGTERM/, 'the spectator gets the last Bye too');
  await exited;
  const stats = JSON.parse(readFileSync(statsFile, 'utf8'));
  const line = stats.scoreboard.find((l) => l.name === 'probe');
  assert.ok(line, 'the probe is on the server\'s scoreboard');
  assert.ok(line.shots >= shotsAfter, `the server counted ${line.shots} of the probe's shots`);
  assert.equal(await hudScore(), line.score, 'the HUD shows the server\'s score');
  console.log(`score ${line.score} on the HUD and in the server's --stats-json, ${line.shots} shots`);
  assert.deepEqual(problems, [], 'no errors in the page');
  assert.deepEqual(eyeProblems, [], 'no errors in the spectator\'s page');
});

test('confirmed hits are marked, and ?debug=lag draws the targets as each shot\'s view held them', { timeout: 60000 }, async () => {
  // Rocks easier to hit (a wide bullet that flies 200 m, not 48: the nearest rock is often
  // farther than that; a short cooldown) and a ship that is never out.
  const config = join(dir, 'hits.json');
  writeFileSync(config, JSON.stringify({ preset: 'asteroids', rules: 'asteroids',
    rules_params: { bullet_radius: 1, bullet_lifetime_ticks: 300, fire_cooldown_ticks: 3, max_bullets_per_ship: 16, lives: 1000 } }));
  const hits = await startServer(server, ['--port', '0', '--http-port', '0', '--config', config, '--drain-grace', '1']);
  try {
    const { page: shooter, problems } = await open('shooter', '&debug=lag', hits.url);
    assert.equal(await shooter.evaluate(() => window.arenaPage.debugLag), true, '?debug=lag read');
    // Turn towards the nearest rock (as the page draws it) and fire until the server confirms hits.
    // Until the server confirmed 3 and the page saw one (a far rock can be hit by a bullet that
    // left the drawn view: confirmed, never seen).
    const counts = () => shooter.evaluate(() => ({ confirmed: window.arenaPage.hitsConfirmed, claimed: window.arenaPage.hitsClaimed }));
    await fireAtNearest(shooter, [2], 20000, async () => {
      const { confirmed, claimed } = await counts();
      return confirmed >= 3 && claimed >= 1;
    });
    const during = await shooter.evaluate(() => ({
      hits: window.arenaPage.hitsConfirmed,
      claimed: window.arenaPage.hitsClaimed,
      hud: document.getElementById('hits').dataset.total,
      shown: !document.getElementById('hits').hidden,
      lagShots: window.arenaPage.lagShots,
      lagJudged: window.arenaPage.lagJudged,
      lagShapesDrawn: window.arenaPage.lagShapesDrawn,
      serverHits: window.arenaPage.client.players.get(window.arenaPage.playerId)?.hits ?? 0,
      view: window.arenaPage.client.viewMoment,
      tick: window.arenaPage.client.session.viewTick,
    }));
    console.log(`the page saw ${during.claimed} hits, the server confirmed ${during.hits} (its scoreboard: ${during.serverHits}); ?debug=lag showed ${during.lagShots} shots and ${during.lagJudged} judged hitboxes, ` +
                `${during.lagShapesDrawn} outlined targets over the frames; the view drawn ${during.view ? during.tick - during.view.tick : '?'} ticks behind the newest snapshot`);
    assert.ok(during.hits > 0, 'the server confirmed hits of the shooter');
    assert.ok(during.claimed > 0, 'the page flashed the hits it saw before any verdict');
    assert.equal(Number(during.hud), during.hits, 'the HUD counts them');
    assert.ok(during.lagShots > 0, 'the overlay showed shots');
    // The hits the server judged in the past (the page's inputs carry their view's moment) came
    // with where: each drew its hitbox.
    assert.ok(during.lagJudged > 0 && during.lagJudged <= during.hits, 'the overlay drew the hitboxes of hits the server judged in the past');
    assert.ok(during.lagShapesDrawn > 0, 'the overlay drew their targets');
    assert.ok(during.view && during.view.tick < during.tick, 'the inputs carry a view behind the newest snapshot');
    // The overlay fades: a second after the last shot it draws nothing.
    await until('the overlay faded', () => shooter.evaluate(() => window.arenaPage.lagShapes === 0), 4000);
    assert.deepEqual(problems, [], 'no errors in the page');
    await shooter.close();
  } finally {
    if (hits.proc.exitCode === null) hits.proc.kill('SIGKILL');
  }
});
