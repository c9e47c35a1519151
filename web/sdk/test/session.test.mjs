// A real match's session, recorded from the native build (arena-sdk-record-session), made
// again on the WebAssembly build: every answer equal byte for byte: the frames it encodes, the
// views it decodes from delta snapshots, the shapes it holds, the predicted own body. Once in
// that match the inputs of three ticks go at once, and the session's input pacing then leaves
// a tick's input out, as the bots' client core does.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { test } from 'node:test';
import { fixtures, fromBase64, loadCore, protocol, sdk } from './helpers.mjs';

const recorded = JSON.parse(fs.readFileSync(path.join(fixtures, 'session.json'), 'utf8'));

test('the WebAssembly session answers every call of a native session over a real match identically', async () => {
  const core = await loadCore();
  const session = new sdk.CoreSession(core);
  let snapshots = 0, deltas = 0, predicted = 0, inputs = 0, views = 0, shots = 0;
  // The own bullets where the prediction has them, bit for bit the native build's; counts the
  // calls after which one was predicted only, and after which one was confirmed.
  const predictedOnly = new Set(), confirmed = new Set();
  const checkBullets = (call, where) => {
    assert.deepEqual(session.ownBulletsBytes(), fromBase64(call.bullets), `${where}: the own bullets`);
    const bullets = session.ownBullets();
    for (const b of bullets) (b.bodyId === 0 ? predictedOnly : confirmed).add(b.sequence);
    return bullets.length > 0 ? 1 : 0;
  };
  for (const [i, call] of recorded.calls.entries()) {
    const where = `call ${i}`;
    if (call.hello) {
      assert.deepEqual(session.hello(...call.hello), fromBase64(call.out), where);
    } else if (call.input) {
      assert.deepEqual(session.input(...call.input), fromBase64(call.out), where);
      ++inputs;
      shots += checkBullets(call, where);
    } else {
      const frame = fromBase64(call.feed);
      assert.equal(session.feed(frame), call.type, `${where}: ${session.error()}`);
      if (call.type === sdk.Payload.Snapshot) {
        ++snapshots;
        if (frame.length > 0 && call.delta_problem === '') ++views;
        assert.equal(session.deltaProblem(), call.delta_problem, where);
        assert.equal(session.viewTick, call.tick, where);
        assert.deepEqual(session.viewBytes(), fromBase64(call.view), `${where}: the decoded view`);
        assert.equal(session.shapes().length, call.shapes, where);
        if (session.deltaAck !== 0) ++deltas;
      }
      shots += checkBullets(call, where);
      if (call.predicted) {
        assert.deepEqual(session.predictedBytes(), fromBase64(call.predicted), `${where}: the predicted body`);
        ++predicted;
      } else {
        assert.equal(session.predicted(), null, where);
      }
    }
  }
  assert.equal(session.ended(), false, session.error());
  assert.equal(recorded.dropped, 2, 'two snapshots lost on the way');
  assert.ok(snapshots > 150 && deltas > 100 && predicted > 100 && inputs > 500,
            `snapshots ${snapshots}, with a delta ack ${deltas}, predicted ${predicted}, inputs ${inputs}`);
  // Shots were fired, seen first as predicted and then as the server's bullets.
  const both = [...predictedOnly].filter((s) => confirmed.has(s));
  assert.ok(shots > 50 && both.length >= 5, `calls with own bullets ${shots}, shots predicted then confirmed ${both.length}`);
  assert.ok(session.shapes().length > 0, 'the view holds shapes');
  session.dispose();
});

test('after two delta snapshots in a row with extra inputs waiting the next input is left out, and the sequences stay consecutive', async () => {
  const core = await loadCore();
  const session = new sdk.CoreSession(core);
  // protocol/README.md, "Input pacing": a non-zero extra_inputs_waiting in two snapshots in a
  // row, both acknowledging an input sent after the last gap, leaves the next tick's out.
  let inARow = 0, due = false, countsFrom = 0, sequence = 0, leftOut = 0, inputs = 0;
  let waitingSeen = 0, zeroSnapshots = 0, lastExtra = -1, sentAfterGap = 0;
  for (const [i, call] of recorded.calls.entries()) {
    const where = `call ${i}`;
    if (call.hello) {
      session.hello(...call.hello);
    } else if (call.input) {
      const frame = session.input(...call.input);
      ++inputs;
      if (due) {
        assert.equal(frame.length, 0, `${where}: this tick's input is left out`);
        due = false;
        ++leftOut;
        countsFrom = sequence + 1;
        sentAfterGap = 0;
        continue;
      }
      assert.ok(frame.length > 0, `${where}: an Input`);
      assert.equal(sdk.readMessage(frame).payload(new protocol.Input()).sequence(), ++sequence, `${where}: the next sequence`);
      ++sentAfterGap;
      assert.equal(session.inputsLeftOut, leftOut, where);
    } else {
      const frame = fromBase64(call.feed);
      assert.equal(session.feed(frame), call.type, `${where}: ${session.error()}`);
      if (call.type !== sdk.Payload.Snapshot || session.deltaProblem() !== '') continue;
      const snapshot = sdk.readMessage(frame).payload(new protocol.Snapshot());
      lastExtra = snapshot.extraInputsWaiting();
      if (lastExtra > 0) ++waitingSeen;
      else ++zeroSnapshots;
      if (snapshot.ackSequence() < countsFrom) continue;
      inARow = lastExtra > 0 ? inARow + 1 : 0;
      if (inARow >= 2) {
        due = true;
        inARow = 0;
      }
    }
  }
  assert.equal(session.ended(), false, session.error());
  assert.ok(zeroSnapshots > 150, `${zeroSnapshots} snapshots with none waiting beyond the first`);
  assert.ok(waitingSeen >= 2, `${waitingSeen} snapshots with extra inputs waiting`);
  assert.equal(leftOut, recorded.inputs_left_out, "as many left out as the native session's");
  assert.ok(leftOut >= 1 && session.inputsLeftOut === leftOut, `left out ${leftOut}, the session says ${session.inputsLeftOut}`);
  assert.equal(sequence + leftOut, inputs, 'every other tick sent the next sequence');
  assert.ok(sentAfterGap > 100, `${sentAfterGap} inputs sent after the gap, none left out`);
  assert.equal(lastExtra, 0, 'the queue drained back to one input waiting');
  session.dispose();
});

test('frames that are not one verified message end the session with a reason', async () => {
  const core = await loadCore();
  const welcome = fromBase64(recorded.calls.find((c) => c.type === sdk.Payload.Welcome).feed);

  const cut = new sdk.CoreSession(core);
  assert.equal(cut.feed(welcome.subarray(0, welcome.length - 3)), 0);
  assert.match(cut.error(), /not exactly one frame/);

  const flipped = welcome.slice();
  flipped[4] ^= 0xff;  // inside the root offset
  const bad = new sdk.CoreSession(core);
  assert.equal(bad.feed(flipped), 0);
  assert.match(bad.error(), /invalid message from the server/);

  const twice = new sdk.CoreSession(core);
  assert.equal(twice.feed(welcome), sdk.Payload.Welcome);
  assert.equal(twice.feed(welcome), 0);
  assert.match(twice.error(), /unexpected Welcome from the server while playing/);
  for (const s of [cut, bad, twice]) s.dispose();
});
