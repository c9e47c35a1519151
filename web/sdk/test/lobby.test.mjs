// The lobby calls (GET and POST /matches) over a fake fetch that answers as the server does,
// and joinOrCreate / join sending Hello.mode and Hello.match through the WebAssembly core.
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { loadCore, protocol, sdk } from './helpers.mjs';

class FakeSocket {
  binaryType = 'blob';
  sent = [];
  onopen = null; onmessage = null; onclose = null; onerror = null;
  send(data) { this.sent.push(new Uint8Array(data)); }
  close() {}
}

function fakeFetch(routes, calls) {
  return async (url, init = {}) => {
    calls.push({ url, ...init });
    const key = `${init.method ?? 'GET'} ${new URL(url).pathname}`;
    const [status, body] = routes[key] ?? [404, { error: 'no route' }];
    return { ok: status >= 200 && status < 300, status, text: async () => JSON.stringify(body) };
  };
}

const duel = { id: '9f1c2e7a40b3d815', mode: 'duel', players: 1, capacity: 2, spectators: 0, tick: 90, state: 'open', created: '2026-12-03T20:41:07Z', private: false };

test('listMatches and getMatch read the lobby; errors carry the server\'s reason', async () => {
  const calls = [];
  const fetch = fakeFetch({ 'GET /matches': [200, [duel]], [`GET /matches/${duel.id}`]: [200, duel], 'GET /matches/nope': [404, { error: "no match 'nope'" }] }, calls);
  assert.deepEqual(await sdk.listMatches('http://h:8080/', { fetch }), [duel]);
  assert.equal(calls[0].url, 'http://h:8080/matches');
  assert.deepEqual(await sdk.getMatch('http://h:8080', duel.id, { fetch }), duel);
  await assert.rejects(sdk.getMatch('http://h:8080', 'nope', { fetch }), /HTTP 404: no match 'nope'/);
});

test('createMatch posts the mode and privacy, with the token when given', async () => {
  const calls = [];
  const fetch = fakeFetch({ 'POST /matches': [201, { ...duel, private: true }] }, calls);
  const made = await sdk.createMatch('http://h:8080', 'duel', true, { fetch, token: 'signed' });
  assert.equal(made.private, true);
  assert.equal(calls[0].method, 'POST');
  assert.deepEqual(JSON.parse(calls[0].body), { mode: 'duel', private: true });
  assert.equal(calls[0].headers.Authorization, 'Bearer signed');
  const refusing = fakeFetch({ 'POST /matches': [503, { error: 'the server holds as many matches as it may (2)' }] }, []);
  await assert.rejects(sdk.createMatch('http://h:8080', 'duel', false, { fetch: refusing }), /HTTP 503: the server holds/);
});

test('joinOrCreate sends Hello.mode, join sends Hello.match, connect neither', async () => {
  const core = await loadCore();
  async function helloOf(open) {
    let socket;
    await open({ core, socket: () => (socket = new FakeSocket()), autoPump: false });
    socket.onopen({});
    return sdk.readMessage(socket.sent[0]).payload(new protocol.Hello());
  }
  const byMode = await helloOf((o) => sdk.joinOrCreate('ws://h/ws', 'ada', 'duel', '', o));
  assert.equal(byMode.mode(), 'duel');
  assert.equal(byMode.match(), null);
  assert.equal(byMode.name(), 'ada');
  const byId = await helloOf((o) => sdk.join('ws://h/ws', 'bob', duel.id, '', o));
  assert.equal(byId.match(), duel.id);
  assert.equal(byId.mode(), null);
  const plain = await helloOf((o) => sdk.connect('ws://h/ws', 'cy', '', o));
  assert.equal(plain.match(), null);
  assert.equal(plain.mode(), null);
});
