// The golden recording replays in WebAssembly to the native build's hashes, every tick. And
// the replayed game as the replay player reads it (ReplayPlayer: manifest, scoreboard, teams,
// events, result): a soccer match recorded at build time (fixtures/record_soccer.cpp) against
// what arena-replay computes natively from the same file, at the end and midway, with a seek
// back rebuilding the event log; Asteroids' own columns; a sandbox recording with none.
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { test } from 'node:test';
import { dist, fixtures, loadCore, sdk, sourceDir } from './helpers.mjs';

const replayBinary = process.env.ARENA_REPLAY;

for (const name of ['golden_asteroids.arpl', 'golden_asteroids_rules.arpl', 'golden_pyramid.arpl']) {
  test(`${name}: every per-tick hash of the WebAssembly world equals the native one`, async () => {
    const file = path.join(sourceDir, 'tests/data', name);
    const native = execFileSync(replayBinary, ['--dump-hashes', file], { encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'] });
    const summary = execFileSync(replayBinary, [file], { encoding: 'utf8' });
    const nativeFinal = /final_hash=([0-9a-f]{16})/.exec(summary)[1];

    const core = await loadCore();
    const result = core.replay(new Uint8Array(fs.readFileSync(file)));
    assert.equal(result.error, '');
    assert.ok(result.ok, 'the replay checks every recorded hash');
    const wasm = 'tick,hash\n' + result.hashes.map((h) => `${h.tick},${h.hash}\n`).join('');
    const nativeLines = native.trimEnd().split('\n');
    assert.ok(nativeLines.length > 100, `${nativeLines.length - 1} native tick hashes`);
    assert.equal(result.hashes.length, nativeLines.length - 1);
    assert.equal(wasm, native);
    assert.equal(result.finalHash, nativeFinal);
    console.log(`${name}: ${result.hashes.length} tick hashes equal, final ${result.finalHash} at tick ${result.finalTick}`);
  });
}

test('a recording with a flipped byte is refused with a reason', async () => {
  const core = await loadCore();
  const bytes = new Uint8Array(fs.readFileSync(path.join(sourceDir, 'tests/data/golden_asteroids.arpl')));
  bytes[bytes.length - 20] ^= 0xff;
  const result = core.replay(bytes);
  assert.equal(result.ok, false);
  assert.match(result.error, /\S/);
});

test('the WebAssembly module size', () => {
  const size = fs.statSync(path.join(dist, 'arena_core.wasm')).size;
  const loader = fs.statSync(path.join(dist, 'arena_core.mjs')).size;
  const bundle = fs.statSync(path.join(dist, 'arena-sdk.mjs')).size;
  console.log(`sdk sizes: arena_core.wasm ${size} bytes, arena_core.mjs ${loader} bytes, arena-sdk.mjs ${bundle} bytes`);
  assert.ok(size > 0);
});

// --- the replayed game ------------------------------------------------------------------------

const soccerFile = () => path.join(fixtures, 'soccer.arpl');
const golden = (name) => path.join(sourceDir, 'tests/data', name);
// arena-replay's scoreboard (what --stats-json holds) where the replay stops: at `until`, else the end.
function nativeBoard(file, until) {
  const args = ['--scoreboard', ...(until === undefined ? [] : ['--until', String(until)]), file];
  return JSON.parse(execFileSync(replayBinary, args, { encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'] }));
}
// The player's scoreboard as arena-replay prints it: the protocol's columns, the team, the name
// and the game's declared fields by name.
function asNative(lines, game) {
  return lines.map((l) => {
    const out = { player: l.playerId, name: l.name, score: l.score, kills: l.kills, deaths: l.deaths, shots: l.shots, hits: l.hits };
    if (l.team !== 0) out.team = l.team;
    game?.playerFields.forEach((f, k) => {
      if (!(f.name in out)) out[f.name] = l.values[k];
    });
    return out;
  });
}
const byKey = (o) => JSON.stringify(Object.fromEntries(Object.entries(o).sort(([a], [b]) => a.localeCompare(b))));
const sameBoard = (lines, game, native, what) =>
  assert.deepEqual(asNative(lines, game).map(byKey), native.map(byKey), `${what}: the scoreboard arena-replay gives`);

test('a replayed soccer match: its manifest, and the scoreboard, names, teams, events and result it reached', async () => {
  const core = await loadCore();
  const player = sdk.ReplayPlayer.open(core, new Uint8Array(fs.readFileSync(soccerFile())));
  try {
    const game = player.manifest;
    assert.equal(game?.name, 'soccer', 'the manifest the rules declare, decoded as a Welcome\'s');
    assert.deepEqual(game.playerFields.map((f) => f.label), ['Team', 'Goals', 'Kicks']);
    assert.deepEqual(game.teams.map((t) => t.name), ['red', 'blue']);
    assert.equal(player.manifest, game, 'decoded once');
    // The start: nobody has joined, nothing has happened.
    assert.deepEqual(player.scoreboard(), []);
    assert.deepEqual(player.events(), []);
    assert.deepEqual(player.result(), { finished: false, winningTeam: 0, winners: [] });

    assert.ok(player.seek(player.endTick), player.error);
    const lines = player.scoreboard();
    sameBoard(lines, game, nativeBoard(soccerFile()), 'the end');
    const joined = ['ana', 'bo', 'cy', 'di', 'ed', 'flo'];
    assert.ok(lines.length >= 4 && lines.every((l) => joined.includes(l.name)), `the names the recording holds: ${lines.map((l) => l.name)}`);
    assert.ok(lines.some((l) => l.values[2] > 0), 'kicks were counted');
    const teams = player.teams();
    assert.deepEqual(teams.map((t) => t.team), [1, 2]);

    const events = player.events();
    const kinds = events.map((e) => game.events[e.kind].name);
    console.log(`soccer fixture: ${events.length} events (${kinds.join(', ')}), red ${teams[0].values[0]}, blue ${teams[1].values[0]}`);
    assert.deepEqual(events.map((e) => e.sequence), events.map((_, i) => i + 1), 'each event once, numbered from the start');
    assert.ok(events.every((e, i) => i === 0 || e.tick >= events[i - 1].tick), 'in tick order');
    // Every goal is an event naming the team it counts for: the events add up to the teams' goals.
    for (const t of teams) {
      const told = events.filter((e) => ['goal', 'own_goal'].includes(game.events[e.kind].name) && e.values[1] === t.team).length;
      assert.equal(told, t.values[0], `${game.teams[t.team - 1].name}'s goals, event by event`);
    }
    assert.ok(kinds.some((k) => k === 'goal' || k === 'own_goal'), 'the fixture has a goal');
    // The clock ran out: the last event is full time, naming the team the result names.
    const result = player.result();
    const [red, blue] = teams.map((t) => t.values[0]);
    assert.equal(result.finished, true);
    assert.equal(result.winningTeam, red === blue ? 0 : red > blue ? 1 : 2);
    assert.deepEqual(result.winners, lines.filter((l) => l.team === result.winningTeam).map((l) => l.playerId));
    assert.equal(kinds.at(-1), 'full_time');
    assert.equal(events.at(-1).values[0], result.winningTeam);
    // A goal's scorer may have left since (di did): the recording still names every player.
    for (const e of events.filter((e) => game.events[e.kind].values[0] === 'player'))
      assert.match(player.nameOf(e.values[0]), /^[a-z]+$/, `player ${e.values[0]} of event ${e.sequence}`);
    assert.equal(player.nameOf(4), 'di');
    assert.equal(player.nameOf(99), '', 'nobody of that id joined');
  } finally {
    player.close();
  }
});

test('seeking back rebuilds the scoreboard and the event log as they were at that tick', async () => {
  const core = await loadCore();
  const bytes = new Uint8Array(fs.readFileSync(soccerFile()));
  const player = sdk.ReplayPlayer.open(core, bytes);
  const stepped = sdk.ReplayPlayer.open(core, bytes);
  try {
    assert.ok(player.seek(player.endTick), player.error);
    const all = player.events();
    const first = all[0];
    assert.ok(first, 'an event to seek around');
    const game = player.manifest;
    // Just before the first event, at it, and back at the end.
    assert.ok(player.seek(first.tick - 1), player.error);
    assert.deepEqual(player.events(), []);
    assert.equal(player.result().finished, false);
    sameBoard(player.scoreboard(), game, nativeBoard(soccerFile(), first.tick - 1), `tick ${first.tick - 1}`);
    assert.ok(player.seek(first.tick), player.error);
    assert.deepEqual(player.events(), [first]);
    const middle = Math.floor((player.startTick + player.endTick) / 2);
    assert.ok(player.seek(middle), player.error);
    assert.deepEqual(player.events(), all.filter((e) => e.tick <= middle));
    sameBoard(player.scoreboard(), game, nativeBoard(soccerFile(), middle), `tick ${middle}`);
    assert.ok(player.seek(player.endTick), player.error);
    assert.deepEqual(player.events(), all, 'the same log at the end again');
    // Stepped a few ticks at a time, as a page plays it: the same log.
    while (stepped.tick < stepped.endTick) assert.ok(stepped.step(37), stepped.error);
    assert.deepEqual(stepped.events(), all);
    assert.deepEqual(stepped.teams(), player.teams());
  } finally {
    player.close();
    stepped.close();
  }
});

test('Asteroids declares no fields: the scoreboard is the protocol\'s own columns, as arena-replay gives them', async () => {
  const core = await loadCore();
  const player = sdk.ReplayPlayer.open(core, new Uint8Array(fs.readFileSync(golden('golden_asteroids_rules.arpl'))));
  try {
    assert.equal(player.manifest?.name, 'asteroids');
    assert.deepEqual(player.manifest.playerFields, []);
    assert.ok(player.seek(player.endTick), player.error);
    const lines = player.scoreboard();
    assert.ok(lines.some((l) => l.score > 0), 'somebody scored');
    sameBoard(lines, player.manifest, nativeBoard(golden('golden_asteroids_rules.arpl')), 'the end');
    assert.deepEqual(player.teams(), []);
    assert.deepEqual(player.events(), [], 'its events are the protocol\'s GameEvents, none declared');
  } finally {
    player.close();
  }
});

test('a sandbox recording: no manifest, no scoreboard, no events, no result', async () => {
  const core = await loadCore();
  const player = sdk.ReplayPlayer.open(core, new Uint8Array(fs.readFileSync(golden('golden_asteroids.arpl'))));
  try {
    assert.ok(player.seek(player.endTick), player.error);
    assert.equal(player.manifest, null);
    assert.deepEqual(player.scoreboard(), []);
    assert.deepEqual(player.teams(), []);
    assert.deepEqual(player.events(), []);
    assert.deepEqual(player.result(), { finished: false, winningTeam: 0, winners: [] });
  } finally {
    player.close();
  }
});
