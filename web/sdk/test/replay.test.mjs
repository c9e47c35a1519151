// The golden recording replays in WebAssembly to the native build's hashes, every tick.
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { test } from 'node:test';
import { dist, loadCore, sourceDir } from './helpers.mjs';

const replayBinary = process.env.ARENA_REPLAY;

for (const name of ['golden_asteroids.arpl', 'golden_asteroids_rules.arpl']) {
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
