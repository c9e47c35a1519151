// A client built before a game existed joins a server playing it (issue 29: "a stale client
// meets a game it does not know ... or watches it as plain bodies"). The recorded match
// (arena-sdk-record-session) is played again with its Welcome renamed: the world config's
// "rules" and the manifest's name say `spaceball`, a game no build has, and the config hash is
// made right again, as a newer server would send it. The client joins, gets every snapshot,
// draws its bodies with their kinds and shapes and its own body predicted, sends the inputs a
// native client sends (the same fields; the bytes until the first draw, after which they carry
// the moment drawn), and nothing ends the session: the world config reader takes any
// well-formed rules name and nothing on the client's path needs the game's code.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { test } from 'node:test';
import { fixtures, fromBase64, loadCore, protocol, sdk } from './helpers.mjs';

const recorded = JSON.parse(fs.readFileSync(path.join(fixtures, 'session.json'), 'utf8'));
const KNOWN = 'asteroids';
const UNKNOWN = 'spaceball';  // as long as KNOWN, so that the frame keeps its layout

// FNV-1a 64 (protocol/README.md, world_config_hash).
function fnv1a64(bytes) {
  let h = 0xcbf29ce484222325n;
  for (const b of bytes) h = BigInt.asUintN(64, (h ^ BigInt(b)) * 0x100000001b3n);
  return h;
}

function indexOf(haystack, needle, from = 0) {
  outer: for (let i = from; i + needle.length <= haystack.length; ++i) {
    for (let k = 0; k < needle.length; ++k) if (haystack[i + k] !== needle[k]) continue outer;
    return i;
  }
  return -1;
}

function replaceOnce(frame, from, to, what) {
  const at = indexOf(frame, from);
  assert.ok(at >= 0, `${what} is in the Welcome`);
  assert.equal(indexOf(frame, from, at + 1), -1, `${what} is in the Welcome once`);
  frame.set(to, at);
}

// The Welcome with the game renamed: the rules in the world config, the manifest's name (a
// nested buffer, so the same bytes edited in place), and the config's hash.
function renamed(frame) {
  const out = frame.slice();
  const welcome = sdk.readMessage(frame).payload(new protocol.Welcome());
  const text = new TextEncoder();
  const config = welcome.worldConfig();
  const rules = new RegExp(`("rules":\\s*)"${KNOWN}"`);
  assert.match(config, rules, 'the recorded world config names the game');
  const newConfig = config.replace(rules, `$1"${UNKNOWN}"`);
  replaceOnce(out, text.encode(config), text.encode(newConfig), 'the world config');
  const hash = (h) => {
    const b = new Uint8Array(8);
    new DataView(b.buffer).setBigUint64(0, h, true);
    return b;
  };
  assert.equal(welcome.worldConfigHash(), fnv1a64(text.encode(config)));
  replaceOnce(out, hash(welcome.worldConfigHash()), hash(fnv1a64(text.encode(newConfig))), 'the config hash');
  // The manifest's name. Welcome.preset names the world's scene (a world preset every build
  // has), not the game: it stays.
  const manifest = welcome.gameArray();
  const nameAt = indexOf(manifest, text.encode(KNOWN));
  assert.ok(nameAt >= 0, 'the manifest names the game');
  const manifestAt = indexOf(out, manifest);
  out.set(text.encode(UNKNOWN), manifestAt + nameAt);
  return out;
}

test('a client that does not know the game joins it, plays and draws it as plain bodies', async () => {
  const core = await loadCore();
  let socket;
  let now = 1000;
  const sent = [];
  const fake = () => (socket = {
    binaryType: 'blob', onopen: null, onmessage: null, onclose: null, onerror: null,
    send: (data) => sent.push(new Uint8Array(data)),
    close: (code, reason) => assert.fail(`the client closed the socket: ${code} ${reason}`),
  });
  const client = await sdk.connect('ws://test/ws', 'fixture', '', { core, socket: fake, now: () => now, autoPump: false });
  let welcome = null;
  let snapshots = 0;
  const byes = [];
  const errors = [];
  client.on('welcome', (w) => (welcome = w));
  client.on('snapshot', (s) => { ++snapshots; if (s.predictionError !== null) errors.push(s.predictionError); });
  client.on('bye', (b) => byes.push(b));
  socket.onopen({});

  let ticks = 0, welcomeAt = 0, drawn = 0;
  const kinds = new Set();
  for (const call of recorded.calls) {
    if (call.feed) {
      let frame = fromBase64(call.feed);
      if (call.type === sdk.Payload.Welcome) {
        frame = renamed(frame);
        welcomeAt = now;
      }
      socket.onmessage({ data: frame.buffer.slice(frame.byteOffset, frame.byteOffset + frame.length) });
      assert.deepEqual(byes, [], 'nothing ends the session');
    } else if (call.input) {
      client.input(...call.input);
      ++ticks;
      now = welcomeAt + (ticks * 1000) / 60 + 0.5;
      const drawnMoment = client.viewMoment;
      client.pump(now);
      // The inputs a client that knows the game sends: they name no game. Once drawn, they
      // carry the moment drawn (lag compensation), which the native session was never told.
      const inputs = sent.splice(0).filter((f) => sdk.readMessage(f).payloadType() === sdk.Payload.Input);
      if (call.out !== '' && drawnMoment === null) assert.deepEqual(inputs[0], fromBase64(call.out), `Input ${ticks}`);
      else if (call.out !== '') {
        const read = sdk.readMessage(inputs[0]).payload(new protocol.Input());
        const native = sdk.readMessage(fromBase64(call.out)).payload(new protocol.Input());
        for (const field of ['sequence', 'thrust', 'turn', 'buttons', 'snapshotAck', 'earlierLength'])
          assert.equal(read[field](), native[field](), `Input ${ticks}: ${field}`);
        assert.equal(read.viewTick(), drawnMoment.tick, `Input ${ticks}: the moment drawn`);
      }
    }
    if (call.feed && call.type === sdk.Payload.Snapshot && snapshots > 10) {
      const state = client.stateAt(now);
      assert.ok(state.own && state.own.predicted, 'the own body is drawn, predicted');
      for (const b of state.bodies) {
        if (b.shape === undefined) continue;
        kinds.add(b.kind);
        ++drawn;
      }
    }
  }
  assert.ok(welcome, 'the Welcome came');
  assert.equal(JSON.parse(welcome.worldConfig).rules, UNKNOWN);
  assert.equal(welcome.game?.name, UNKNOWN, 'the manifest, read as any game\'s');
  assert.ok(welcome.game.bodyTags.length > 0, 'with its body tags to draw by');
  assert.ok(snapshots > 150, `${snapshots} snapshots`);
  assert.ok(drawn > 1000, `${drawn} bodies drawn with their shapes`);
  // Ships 1, rocks 2 and bullets 3: the kinds the server sent, whatever the client knows.
  assert.ok(kinds.has(1) && kinds.has(2), `the kinds drawn: ${[...kinds]}`);
  assert.ok(errors.length > 100 && errors.every((e) => e < 2), 'the own body predicted, its errors small');
  assert.equal(client.session.ended(), false, client.session.error());
  assert.deepEqual(byes, []);
});
