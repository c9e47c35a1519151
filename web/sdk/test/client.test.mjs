// connect() over a fake socket that plays a real match's frames (recorded from the native
// build): the Hello and every Input the SDK sends equal the native session's bytes and read
// back through the generated TypeScript to the controls given (frames round trip), and a tick
// whose input the pacing leaves out sends nothing and counts in inputsLeftOut; events
// come; stateAt draws the own body predicted and the others interpolated; close() says Bye.
// A spectator (spectate: true) sends Hello.spectator and no Input, and draws with no own ship.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { test } from 'node:test';
import { fixtures, fromBase64, loadCore, protocol, sdk } from './helpers.mjs';

const recorded = JSON.parse(fs.readFileSync(path.join(fixtures, 'session.json'), 'utf8'));

// Closes as a browser's WebSocket does: a code other than 1000 or 3000-4999 throws
// InvalidAccessError, a reason over 123 bytes of UTF-8 throws SyntaxError.
class FakeSocket {
  binaryType = 'blob';
  sent = [];
  closed = false;
  closeCode = undefined;
  closeReason = undefined;
  onopen = null; onmessage = null; onclose = null; onerror = null;
  send(data) { this.sent.push(new Uint8Array(data)); }
  close(code, reason) {
    if (code !== undefined && code !== 1000 && (code < 3000 || code > 4999))
      throw new DOMException(`close code ${code} is neither 1000 nor in 3000-4999`, 'InvalidAccessError');
    if (reason !== undefined && Buffer.byteLength(reason, 'utf8') > 123)
      throw new DOMException('close reason longer than 123 bytes', 'SyntaxError');
    this.closed = true;
    this.closeCode = code;
    this.closeReason = reason;
  }
}

test('a game client over a fake socket sends what the native session sent and draws the match', async () => {
  const core = await loadCore();
  let socket;
  let now = 1000;
  const client = await sdk.connect('ws://test/ws', 'fixture', '', { core, socket: (url) => (socket = new FakeSocket()), now: () => now, autoPump: false });
  const events = { welcome: 0, snapshot: 0, pong: 0, bye: [] };
  const errors = [];
  client.on('welcome', (w) => { ++events.welcome; assert.equal(w.tickRate, 60); assert.equal(w.world.wraps, true); });
  client.on('snapshot', (s) => { ++events.snapshot; if (s.predictionError !== null) errors.push(s.predictionError); });
  client.on('bye', (b) => events.bye.push(b));
  assert.equal(socket.binaryType, 'arraybuffer');
  socket.onopen({});

  let ticks = 0, welcomeAt = 0, inputs = 0, pings = 0, leftOut = 0;
  for (const call of recorded.calls) {
    if (call.hello) {
      assert.deepEqual(socket.sent.shift(), fromBase64(call.out), 'the Hello');
    } else if (call.feed) {
      const frame = fromBase64(call.feed);
      if (call.type === sdk.Payload.Welcome) welcomeAt = now;
      socket.onmessage({ data: frame.buffer.slice(frame.byteOffset, frame.byteOffset + frame.length) });
    } else if (call.input) {
      client.input(...call.input);
      ++ticks;
      now = welcomeAt + (ticks * 1000) / 60 + 0.5;
      client.pump(now);
      const sent = socket.sent.splice(0);
      const own = sent.filter((f) => sdk.readMessage(f).payloadType() === sdk.Payload.Input);
      pings += sent.length - own.length;
      if (call.out === '') {
        // A tick the input pacing left out (the native session's too): nothing is sent.
        assert.equal(own.length, 0, `no Input on a tick left out (tick ${ticks})`);
        assert.equal(client.inputsLeftOut, ++leftOut);
        continue;
      }
      assert.equal(own.length, 1, `one Input per tick (tick ${ticks})`);
      assert.deepEqual(own[0], fromBase64(call.out), `Input ${ticks}: the native session's bytes`);
      const read = sdk.readMessage(own[0]).payload(new protocol.Input());
      assert.equal(read.sequence(), ticks - leftOut, 'the next sequence, across a tick left out');
      assert.equal(read.thrust(), Math.fround(call.input[0]));
      assert.equal(read.turn(), Math.fround(call.input[1]));
      assert.equal(read.buttons(), call.input[2]);
      ++inputs;
    }
    if (call.feed && call.type === sdk.Payload.Snapshot && events.snapshot > 10) {
      const state = client.stateAt(now);
      assert.ok(state.own && state.own.predicted, 'the own body is drawn, predicted');
      assert.ok(state.bodies.length > 1, 'other bodies are drawn');
      assert.ok(state.bodies.filter((b) => !b.predicted).every((b) => b.id !== state.own.id));
      assert.ok(state.bodies.some((b) => b.shape !== undefined && b.kind === 2), 'rocks come with their shapes');
    }
  }
  assert.equal(events.welcome, 1);
  assert.ok(events.snapshot > 150, `${events.snapshot} snapshots`);
  assert.ok(inputs > 500);
  assert.ok(leftOut >= 1 && client.inputsLeftOut === leftOut, `${leftOut} inputs left out`);
  assert.ok(Math.abs(pings - ticks / 60) <= 1, `${pings} Pings in ${ticks} ticks: one a second`);
  assert.ok(errors.length > 100 && errors.every((e) => e < 2), 'prediction errors measured, small');
  assert.deepEqual(events.bye, []);

  client.close('done');
  const bye = socket.sent.pop();
  assert.equal(sdk.readMessage(bye).payloadType(), sdk.Payload.Bye);
  assert.equal(socket.closed, true);
  assert.equal(events.bye.length, 1);
  assert.equal(events.bye[0].reason, 'done');
});

test('a frame the core refuses ends the session with a bye event that says why', async () => {
  const core = await loadCore();
  let socket;
  const client = await sdk.connect('ws://test/ws', 'x', '', { core, socket: () => (socket = new FakeSocket()), now: () => 0, autoPump: false });
  const byes = [];
  client.on('bye', (b) => byes.push(b));
  socket.onmessage({ data: new Uint8Array([8, 0, 0, 0, 1, 2, 3, 4, 5, 6, 7, 8]).buffer });
  assert.equal(byes.length, 1);
  assert.match(byes[0].reason, /invalid message from the server/);
  assert.equal(socket.closed, true);
  assert.equal(socket.closeCode, sdk.PROTOCOL_ERROR_CLOSE_CODE);
  assert.ok(socket.closeCode >= 4000 && socket.closeCode <= 4999, 'a code a browser lets a page send');
  assert.equal(socket.closeReason, 'protocol error');
});

test('a text message from the server closes with a code a browser accepts, and the bye says why', async () => {
  const core = await loadCore();
  let socket;
  const client = await sdk.connect('ws://test/ws', 'x', '', { core, socket: () => (socket = new FakeSocket()), now: () => 0, autoPump: false });
  const byes = [];
  client.on('bye', (b) => byes.push(b));
  socket.onmessage({ data: 'hello' });
  assert.equal(byes.length, 1);
  assert.equal(byes[0].reason, 'a text message from the server');
  assert.equal(socket.closeCode, sdk.PROTOCOL_ERROR_CLOSE_CODE);
});

test('a spectator says so in its Hello, sends no Input, and draws the whole match with no own ship', async () => {
  const core = await loadCore();
  const watched = recorded.spectator;
  let socket;
  let now = 1000;
  const client = await sdk.connect('ws://test/ws', 'watcher', '', { core, socket: () => (socket = new FakeSocket()), now: () => now, autoPump: false, spectate: true });
  assert.equal(client.spectating, true);
  let welcome = null;
  const counts = [];
  client.on('welcome', (w) => (welcome = w));
  client.on('snapshot', (s) => counts.push(s.bodies.length));
  socket.onopen({});
  const hello = socket.sent.shift();
  assert.deepEqual(hello, fromBase64(watched.hello), "the native spectator session's Hello");
  const read = sdk.readMessage(hello).payload(new protocol.Hello());
  assert.equal(read.spectator(), true);
  assert.equal(read.name(), 'watcher');

  let sentInputs = 0, pings = 0, lastState = null;
  for (const encoded of watched.frames) {
    const frame = fromBase64(encoded);
    socket.onmessage({ data: frame.buffer.slice(frame.byteOffset, frame.byteOffset + frame.length) });
    if (sdk.readMessage(frame).payloadType() !== sdk.Payload.Snapshot) continue;
    now += 50;  // one snapshot interval at 20 Hz
    client.input(1, 1, 1);  // a spectator's controls do nothing
    client.pump(now);
    for (const f of socket.sent.splice(0)) {
      const type = sdk.readMessage(f).payloadType();
      if (type === sdk.Payload.Input) ++sentInputs;
      if (type === sdk.Payload.Ping) ++pings;
    }
    if (counts.length > 10) lastState = client.stateAt(now);
  }
  assert.ok(welcome, 'welcomed');
  assert.ok(welcome.playerId > 0);
  assert.equal(welcome.entityId, 0, 'no body of its own');
  assert.equal(welcome.viewRadius, 0, 'the whole world');
  assert.deepEqual(counts, watched.bodies, 'every snapshot with the bodies the native session decoded');
  assert.ok(counts.length > 150, `${counts.length} snapshots`);
  assert.equal(sentInputs, 0, 'no Input');
  assert.ok(pings > 0, 'Pings keep it from the idle timeout');
  assert.ok(lastState, 'a state to draw');
  assert.equal(lastState.own, null, 'no own ship');
  assert.ok(lastState.bodies.length > 0);
  assert.ok(lastState.bodies.every((b) => !b.predicted && b.owner !== welcome.playerId));
  assert.ok(lastState.bodies.some((b) => b.kind === 1 && b.owner !== 0), "the player's ship is drawn");
  assert.ok(lastState.bodies.some((b) => b.kind === 2), 'rocks with their shapes');
});
