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

// Starts `server` with `args` (its --http-port 0 among them) and waits for its HTTP port: the
// process, a promise of how it exited, and the page's URL.
export async function startServer(server, args, timeoutMs = 15000) {
  const { spawn } = await import('node:child_process');
  const proc = spawn(server, args, { stdio: ['ignore', 'pipe', 'pipe'] });
  const exited = new Promise((resolve) => proc.on('exit', (code, signal) => resolve({ code, signal })));
  let out = '';
  let err = '';
  proc.stdout.on('data', (d) => (out += d));
  proc.stderr.on('data', (d) => (err += d));
  const port = await until('the server\'s http port', () => out.match(/^http listening on .*:(\d+)$/m)?.[1], timeoutMs).catch((e) => {
    throw new Error(`${e.message}\n${out}\n${err}`);
  });
  return { proc, exited, url: `http://127.0.0.1:${port}/` };
}

// A headless Chromium as the browser tests run it.
export function launchBrowser(chromium) {
  return puppeteer.launch({ executablePath: chromium, headless: true, args: ['--no-sandbox', '--disable-gpu'] });
}
