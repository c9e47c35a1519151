// What the browser tests share: their settings from ctest, puppeteer-core, waiting.
import { createRequire } from 'node:module';
import { join } from 'node:path';

export const need = (name) => {
  const v = process.env[name];
  if (!v) throw new Error(`${name} is not set (run this test through ctest)`);
  return v;
};

// ES modules ignore NODE_PATH: load the CommonJS build of puppeteer-core from there.
const require = createRequire(join(need('NODE_PATH'), 'page-test.cjs'));
export const puppeteer = require('puppeteer-core');

export const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

// Polls `check` until it returns something truthy, which it returns.
export async function until(what, check, timeoutMs = 8000) {
  const end = Date.now() + timeoutMs;
  for (;;) {
    const v = await check();
    if (v) return v;
    if (Date.now() > end) throw new Error(`timed out waiting for ${what}`);
    await sleep(50);
  }
}
