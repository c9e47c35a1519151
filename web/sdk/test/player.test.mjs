// The replay player (ReplayPlayer, web/sdk/core/replay_player.hpp): stepping, seeking forward
// and back, and the recorded hashes it checks, on the golden recordings in WebAssembly.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { test } from 'node:test';
import { loadCore, sdk, sourceDir } from './helpers.mjs';
import { withChangedHash } from './recording_edits.mjs';

const golden = (name) => new Uint8Array(fs.readFileSync(path.join(sourceDir, 'tests/data', name)));
const state = (p) => ({ tick: p.tick, hash: p.hash, bodies: JSON.stringify(p.bodies()) });

for (const name of ['golden_asteroids.arpl', 'golden_asteroids_rules.arpl']) {
  test(`${name}: played to the end, every recorded hash checks and the last is the recording's`, async () => {
    const core = await loadCore();
    const whole = core.replay(golden(name));
    const player = sdk.ReplayPlayer.open(core, golden(name));
    try {
      assert.equal(player.tick, player.startTick);
      assert.equal(player.hashesChecked, 1, 'the start hash');
      assert.equal(player.recordedHash, player.hash);
      // Uneven steps, as a page at 0.25x to 8x makes them.
      const sizes = [1, 3, 0, 7, 2, 16];
      for (let i = 0; player.tick < player.endTick; ++i) assert.ok(player.step(sizes[i % sizes.length]), player.error);
      assert.equal(player.tick, player.endTick);
      assert.equal(player.tick, whole.finalTick);
      assert.equal(player.hash, whole.finalHash);
      assert.equal(player.recordedHash, whole.finalHash, 'the End record holds the final hash');
      assert.equal(player.hashesChecked, player.hashesTotal);
      assert.equal(player.hashesChecked, whole.hashesChecked);
      assert.equal(player.error, '');
      assert.ok(!player.step(0) || player.tick === player.endTick, 'no step past the end');
      console.log(`${name}: ${player.hashesChecked}/${player.hashesTotal} hashes, ticks ${player.startTick}..${player.endTick}, final ${player.hash}`);
    } finally {
      player.close();
    }
  });
}

test('seeking forward and back gives the state and hash that stepping from the start gives', async () => {
  const core = await loadCore();
  const bytes = golden('golden_asteroids.arpl');
  const stepped = sdk.ReplayPlayer.open(core, bytes);
  const seeking = sdk.ReplayPlayer.open(core, bytes);
  try {
    const end = stepped.endTick;
    const targets = [Math.floor(end / 2), Math.floor(end / 4), end, stepped.startTick, Math.floor((3 * end) / 4), 1];
    const expected = new Map();
    for (const t of [...targets].sort((a, b) => a - b)) {
      assert.ok(stepped.step(t - stepped.tick), stepped.error);
      expected.set(t, state(stepped));
    }
    for (const t of targets) {
      assert.ok(seeking.seek(t), seeking.error);
      assert.deepEqual(state(seeking), expected.get(t), `seek to ${t}`);
      if (seeking.recordedHash !== '') assert.equal(seeking.recordedHash, seeking.hash);
    }
    assert.ok(seeking.seek(end + 1000));
    assert.equal(seeking.tick, end, 'a seek past the end stops at the end');
    assert.equal(seeking.hashesChecked, seeking.hashesTotal);
    assert.notEqual(expected.get(Math.floor(end / 2)).hash, expected.get(end).hash, 'the states differ along the way');
  } finally {
    stepped.close();
    seeking.close();
  }
});

test('a changed recorded hash: the player stops at its tick and names both hashes', async () => {
  const core = await loadCore();
  const bytes = golden('golden_asteroids.arpl');
  const whole = core.replay(bytes);
  const changed = withChangedHash(bytes, whole.hashes);
  const player = sdk.ReplayPlayer.open(core, changed.bytes);
  try {
    let ok = true;
    while (ok && player.tick < player.endTick) ok = player.step(5);
    assert.equal(ok, false);
    assert.equal(player.tick, changed.tick);
    const wrong = (BigInt('0x' + changed.recorded) ^ 1n).toString(16).padStart(16, '0');
    assert.equal(player.error, `tick ${changed.tick}: hash mismatch: expected ${wrong}, actual ${changed.recorded}`);
    assert.equal(player.hashesChecked, 2, 'the start hash, then the changed one');
    assert.equal(player.step(5), false, 'it stays stopped');
    assert.equal(player.tick, changed.tick);
    // Back to the start and forward again finds the same mismatch.
    assert.ok(player.seek(player.startTick));
    assert.equal(player.seek(player.endTick), false);
    assert.equal(player.tick, changed.tick);
  } finally {
    player.close();
  }
});

test('a recording cut short (no End record) plays up to its last complete tick', async () => {
  const core = await loadCore();
  const bytes = golden('golden_asteroids.arpl');
  const full = sdk.ReplayPlayer.open(core, bytes);
  const cut = sdk.ReplayPlayer.open(core, bytes.slice(0, Math.floor(bytes.length / 2)));
  try {
    assert.equal(full.cutShort, '');
    assert.match(cut.cutShort, /byte offset \d+/);
    assert.ok(cut.endTick > cut.startTick && cut.endTick < full.endTick, `${cut.endTick} of ${full.endTick}`);
    assert.ok(cut.seek(cut.endTick), cut.error);
    assert.ok(full.seek(cut.endTick), full.error);
    assert.equal(cut.hash, full.hash);
    assert.equal(cut.error, '');
  } finally {
    full.close();
    cut.close();
  }
});

test('bytes that are not a recording are refused with a reason', async () => {
  const core = await loadCore();
  assert.throws(() => sdk.ReplayPlayer.open(core, new TextEncoder().encode('not a recording')), /\S/);
});
