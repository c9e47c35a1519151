// The lobby view (?lobby) in a real browser against a real arena-server hosting many matches
// (docs/MATCHES.md), with a mode of two seats from a --modes file: the lobby lists the default
// match, its form creates a private duel and goes into it (the Welcome names that match), a
// second page joins by the HUD's invite link, and the server counts both in that match. An
// unknown mode's refusal shows as one line on the lobby.
//   ARENA_SERVER   the arena-server binary       ARENA_CHROMIUM  the browser
//   NODE_PATH      the page's node_modules (puppeteer-core, from web/page/package-lock.json)
import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import { launchBrowser, need, startServer, until } from './browser.mjs';

const server = need('ARENA_SERVER');
const chromium = need('ARENA_CHROMIUM');

const dir = mkdtempSync(join(tmpdir(), 'arena-lobby-'));
let proc;
let browser;
let url;
const problems = [];

before(async () => {
  const modes = join(dir, 'modes.json');
  writeFileSync(modes, '{"modes": [{"name": "duel", "preset": "asteroids", "max_players": 2}]}');
  ({ proc, url } = await startServer(server, ['--port', '0', '--http-port', '0', '--modes', modes, '--drain-grace', '1']));
  browser = await launchBrowser(chromium);
});

after(async () => {
  await browser?.close();
  if (proc && proc.exitCode === null) proc.kill('SIGKILL');
  rmSync(dir, { recursive: true, force: true });
});

async function open(query) {
  const page = await browser.newPage();
  await page.setViewport({ width: 800, height: 600 });
  page.on('pageerror', (e) => problems.push(`${query}: ${e.message}`));
  // A refused create answers 404, which the browser logs as an error of its own: not the page's.
  page.on('console', (m) => m.type() === 'error' && !/status of 404/.test(m.text()) && problems.push(`${query}: ${m.text()}`));
  await page.goto(`${url}${query}`);
  return page;
}

const lobbyState = (page) => page.evaluate(() => window.arenaPage?.lobby);
const matchInfo = async (id) => (await fetch(`${url}matches/${id}`)).json();
// The match the page has joined, once its Welcome and a few snapshots are in.
const joined = (page, what) =>
  until(what, () => page.evaluate(() => window.arenaPage?.snapshots > 2 && window.arenaPage.match), 15000);

test('the lobby lists the matches, creates a private duel and goes into it; an invitee joins it', { timeout: 60000 }, async () => {
  const lobby = await open('?lobby&name=one');
  const listed = await until('the default match in the lobby', async () => (await lobbyState(lobby))?.matches.find((m) => m.id === 'default'), 15000);
  assert.equal(listed.state, 'open');
  const row = await lobby.evaluate(() => {
    const tr = document.querySelector('#matches tr[data-match="default"]');
    return { text: tr?.innerText, join: tr?.querySelector('a.join')?.getAttribute('href'), watch: tr?.querySelector('a.watch')?.getAttribute('href') };
  });
  assert.match(row.text, /default/);
  assert.equal(row.join, '?match=default&name=one');
  assert.equal(row.watch, '?match=default&spectate');

  // Create a private duel through the form: the page goes into it.
  await lobby.type('#create-mode', 'duel');
  await lobby.click('#create-private');
  await Promise.all([lobby.waitForNavigation({ timeout: 15000 }), lobby.click('#create-submit')]);
  const id = new URL(lobby.url()).searchParams.get('match');
  assert.ok(id && id !== 'default', `the page went to ${lobby.url()}`);
  assert.equal(new URL(lobby.url()).searchParams.get('name'), 'one');
  assert.equal(await joined(lobby, 'the creator\'s Welcome'), id, 'the Welcome names the created match');
  const hud = await lobby.evaluate(() => ({
    mode: window.arenaPage.mode,
    invite: window.arenaPage.invite,
    matchId: document.getElementById('match-id').textContent,
    inviteHref: document.getElementById('invite').href,
  }));
  assert.equal(hud.mode, 'duel');
  assert.equal(hud.matchId, id, 'the HUD shows the match');
  assert.equal(hud.inviteHref, `${url}?match=${id}`, 'the invite link is the page with ?match=ID and nothing else');
  assert.equal(hud.invite, hud.inviteHref);
  const made = await matchInfo(id);
  assert.equal(made.private, true);
  assert.equal(made.mode, 'duel');
  const list = await (await fetch(`${url}matches`)).json();
  assert.ok(!list.some((m) => m.id === id), 'a private match is not listed');

  // A second player comes in by the invite link.
  const two = await open(`?match=${id}&name=two`);
  assert.equal(await joined(two, 'the invitee\'s Welcome'), id);
  const full = await until('two players in the match', async () => {
    const m = await matchInfo(id);
    return m.players === 2 ? m : null;
  });
  assert.equal(full.state, 'full', 'a duel of two is full');
  assert.ok(await lobby.evaluate(() => window.arenaPage.bye === null), 'the creator is still in');

  // A mode the server does not play: the refusal is one line on the lobby, and it stays there.
  const other = await open('?lobby');
  await until('a list', async () => (await lobbyState(other))?.refreshes > 0);
  await other.type('#create-mode', 'nope');
  await other.click('#create-submit');
  const error = await until('the refusal shown', () => other.evaluate(() => {
    const line = document.getElementById('lobby-error');
    return !line.hidden && window.arenaPage.lobby.error === line.textContent ? line.textContent : null;
  }));
  assert.match(error, /404/);
  assert.ok(!error.includes('\n'), 'one line');
  const refreshes = (await lobbyState(other)).refreshes;
  await until('the next refresh', async () => (await lobbyState(other)).refreshes > refreshes);
  assert.equal((await lobbyState(other)).error, error, 'a good refresh leaves the refusal shown');
  assert.equal(new URL(other.url()).search, '?lobby', 'the page stays in the lobby');

  assert.deepEqual(problems, [], 'no errors in the pages');
});
