// What every SDK test needs: the built SDK (ARENA_SDK_DIST, set by ctest) and its core.
import fs from 'node:fs';
import path from 'node:path';

export const dist = process.env.ARENA_SDK_DIST;
export const fixtures = process.env.ARENA_SDK_FIXTURES;
export const sourceDir = process.env.ARENA_SOURCE_DIR;
if (!dist || !fixtures || !sourceDir) {
  throw new Error('ARENA_SDK_DIST, ARENA_SDK_FIXTURES and ARENA_SOURCE_DIR must be set (run through ctest)');
}

export const sdk = await import(path.join(dist, 'arena-sdk.mjs'));

let core;
// One core for the whole test file: loading compiles the module.
export async function loadCore() {
  core ??= await sdk.Core.load({ wasmBinary: fs.readFileSync(path.join(dist, 'arena_core.wasm')) });
  return core;
}

export function fromBase64(text) {
  return new Uint8Array(Buffer.from(text, 'base64'));
}

// The generated schema classes, as the bundle carries them (for reading frames in tests).
export const protocol = sdk.protocol;
