// connect() over a fake socket that plays a real match's frames (recorded from the native
// build): the Hello and every Input the SDK sends equal the native session's bytes and read
// back through the generated TypeScript to the controls given (frames round trip), and a tick
// whose input the pacing leaves out sends nothing and counts in inputsLeftOut; events
// come; stateAt draws the own body predicted and the others interpolated; close() says Bye.
// A spectator (spectate: true) sends Hello.spectator and no Input, and draws with no own ship.
// Once it draws, each Input carries the moment of the view drawn last (lag compensation): a
// tick behind the newest snapshot's by about the interpolation delay, with a fraction.
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
      // The native session was never told a view moment: its bytes are the SDK's until the
      // first draw, after which the SDK's Inputs carry the moment drawn (tested below).
      const drawn = client.viewMoment;
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
      const read = sdk.readMessage(own[0]).payload(new protocol.Input());
      const native = sdk.readMessage(fromBase64(call.out)).payload(new protocol.Input());
      if (drawn === null) assert.deepEqual(own[0], fromBase64(call.out), `Input ${ticks}: the native session's bytes`);
      else {
        assert.equal(read.viewTick(), drawn.tick, `Input ${ticks}: the moment drawn`);
        assert.equal(read.viewFraction(), drawn.fraction);
        assert.equal(read.snapshotAck(), native.snapshotAck(), `Input ${ticks}: the native session's acknowledgement`);
        assert.equal(read.earlierLength(), native.earlierLength());
      }
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

test('each Input carries the moment of the view drawn last: behind the newest snapshot by the interpolation delay', async () => {
  const core = await loadCore();
  let socket;
  let now = 1000;
  const client = await sdk.connect('ws://test/ws', 'fixture', '', { core, socket: () => (socket = new FakeSocket()), now: () => now, autoPump: false });
  const announced = [];
  client.on('input', (i) => announced.push(i));
  socket.onopen({});
  socket.sent.splice(0);
  let welcomeAt = 0, ticks = 0, snapshotRate = 0, drawn = 0;
  const carried = [];  // { behind: newest snapshot's tick − view_tick (ticks, with the fraction), delay }
  const fractions = new Set();
  let undrawn = 0;
  for (const call of recorded.calls) {
    if (call.feed) {
      const frame = fromBase64(call.feed);
      if (call.type === sdk.Payload.Welcome) welcomeAt = now;
      socket.onmessage({ data: frame.buffer.slice(frame.byteOffset, frame.byteOffset + frame.length) });
      snapshotRate ||= client.session.snapshotRate;
    } else if (call.input) {
      client.input(...call.input);
      ++ticks;
      now = welcomeAt + (ticks * 1000) / 60 + 0.5;
      client.pump(now);
      for (const f of socket.sent.splice(0)) {
        if (sdk.readMessage(f).payloadType() !== sdk.Payload.Input) continue;
        const read = sdk.readMessage(f).payload(new protocol.Input());
        const said = announced.at(-1);
        assert.equal(said.sequence, read.sequence(), "the 'input' event names the Input sent");
        assert.equal(said.tick, read.viewTick());
        assert.equal(said.fraction, read.viewFraction());
        if (drawn === 0) {
          // Before any draw nothing is told: the core puts the newest snapshot's tick.
          assert.equal(read.viewTick(), client.session.viewTick, 'before a draw: the newest snapshot');
          assert.equal(read.viewFraction(), 0);
          ++undrawn;
          continue;
        }
        const behind = client.session.viewTick - (read.viewTick() + read.viewFraction() / 256);
        carried.push({ behind, delay: (client.buffer.delay * 60) / 1000 });
        fractions.add(read.viewFraction());
      }
      // The page draws a frame after each tick, from the second snapshot on, somewhere in the
      // tick (a display's frames are not the server's ticks): the fraction drawn varies.
      if (client.buffer.size >= 2) {
        const state = client.stateAt(now + ((ticks * 7) % 16));
        assert.deepEqual(state.view, client.viewMoment, 'stateAt says the moment it drew');
        ++drawn;
      }
    }
  }
  assert.ok(undrawn > 0, 'Inputs before the first draw');
  assert.ok(carried.length > 400, `${carried.length} Inputs carried a drawn moment`);
  // The view is the interpolation delay behind the newest snapshot, less the time since that
  // snapshot arrived (up to a snapshot interval) and the fastest trip's share of it: in the
  // middle, and never beyond the delay nor ahead by more than the extrapolation (an interval).
  const interval = 60 / snapshotRate;
  const sorted = carried.map((c) => c.behind).sort((x, y) => x - y);
  const median = sorted[Math.floor(sorted.length / 2)];
  const delay = carried.at(-1).delay;
  console.log(`view moments: ${median.toFixed(2)} ticks behind the newest snapshot (median; from ${sorted[0].toFixed(2)} to ` +
              `${sorted.at(-1).toFixed(2)}), delay ${delay.toFixed(2)} ticks, a snapshot each ${interval} ticks, ${fractions.size} fractions seen`);
  assert.ok(carried.every((c) => Math.abs(c.delay - delay) < 0.01), 'the delay held (no jitter in the recorded frames)');
  assert.ok(median >= delay - interval - 1 && median <= delay + 0.5, `median ${median} ticks behind, the delay ${delay}`);
  assert.ok(sorted[0] >= -interval && sorted.at(-1) <= delay + 1, `from ${sorted[0]} to ${sorted.at(-1)} ticks behind`);
  // The draws fall at 16 offsets within a tick; where the snapshots fall adds a few more.
  assert.ok(fractions.size >= 16, `the fraction varies: ${fractions.size} values`);
});

test('momentOf: a server time as a tick and 1/256 ticks', () => {
  assert.deepEqual(sdk.momentOf(1000, 60), { tick: 60, fraction: 0 });
  assert.deepEqual(sdk.momentOf(1000 + 1000 / 120, 60), { tick: 60, fraction: 128 });
  assert.deepEqual(sdk.momentOf(-5, 60), { tick: 0, fraction: 0 });
});
