// When the SDK ends a session because the server broke the protocol, the page says why. A real
// arena-server and a real headless Chromium, whose WebSocket refuses the close codes a page may
// not send (anything but 1000 and 3000-4999 throws InvalidAccessError: the SDK's old 1002 did,
// and the reason never showed). The page's socket is wrapped before the page loads so that the
// server's first frame, its Welcome, arrives with one letter of its world config changed: the
// core finds the config hash wrong, the SDK closes with 4002 and its bye names the problem,
// which the page's status line shows.
//   ARENA_SERVER  ARENA_CHROMIUM  NODE_PATH (see page.test.mjs)
import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import { launchBrowser, need, startServer, until } from './browser.mjs';

const server = need('ARENA_SERVER');
const chromium = need('ARENA_CHROMIUM');

let proc;
let browser;
let url;

before(async () => {
  ({ proc, url } = await startServer(server, ['--port', '0', '--http-port', '0', '--preset', 'asteroids']));
  browser = await launchBrowser(chromium);
});

after(async () => {
  await browser?.close();
  if (proc && proc.exitCode === null) proc.kill('SIGKILL');
});

// Runs in the page before its scripts: every WebSocket's first binary frame has the first letter
// of its world config's rules name changed (a byte for byte decoding keeps the offsets), and every close(code, reason) is kept in
// window.socketCloses before the browser's own close() checks it.
function corruptTheWelcome() {
  const Real = window.WebSocket;
  window.socketCloses = [];
  // The first letter of the value after `"rules"` (the config is JSON: `"rules": "asteroids"`).
  const corrupt = (bytes) => {
    const text = new TextDecoder('latin1').decode(bytes);
    const key = text.indexOf('"rules"');
    const at = key < 0 ? -1 : text.indexOf('"', text.indexOf(':', key)) + 1;
    if (at <= 0) return false;
    bytes[at] = bytes[at] === 0x7a ? 0x79 : 0x7a;  // 'z', or 'y' for a name starting with 'z'
    return true;
  };
  window.WebSocket = class extends Real {
    set onmessage(handler) {
      let first = true;
      super.onmessage = (ev) => {
        if (first && ev.data instanceof ArrayBuffer) {
          first = false;
          const bytes = new Uint8Array(ev.data.slice(0));
          window.corruptedWelcome = corrupt(bytes);
          return handler({ data: bytes.buffer });
        }
        return handler(ev);
      };
    }
    get onmessage() {
      return super.onmessage;
    }
    close(code, reason) {
      window.socketCloses.push({ code, reason });
      super.close(code, reason);
    }
  };
}

test('a Welcome the core refuses ends the session with a close a browser accepts, and the page shows why', { timeout: 30000 }, async () => {
  const page = await browser.newPage();
  await page.setViewport({ width: 800, height: 600 });
  const problems = [];
  page.on('pageerror', (e) => problems.push(e.message));
  page.on('console', (m) => m.type() === 'error' && problems.push(m.text()));
  await page.evaluateOnNewDocument(corruptTheWelcome);
  await page.goto(`${url}?name=stale`);
  const bye = await until('the bye', () => page.evaluate(() => window.arenaPage?.bye)).catch((e) => {
    throw new Error(`${e.message}: ${problems.join('; ')}`);
  });
  assert.equal(await page.evaluate(() => window.corruptedWelcome), true, 'the Welcome held a rules name to change');
  assert.match(bye.reason, /world_config_hash does not match world_config/);
  assert.deepEqual(await page.evaluate(() => window.socketCloses), [{ code: 4002, reason: 'protocol error' }]);
  const status = await page.$eval('#status', (e) => ({ text: e.textContent, hidden: e.hidden }));
  assert.equal(status.hidden, false, 'the status line shows');
  assert.equal(status.text, `disconnected: ${bye.reason}`);
  assert.equal(await page.evaluate(() => window.arenaPage.playerId), 0, 'never joined');
  assert.deepEqual(problems, [], 'no error in the page: the close code was one a browser accepts');
});
