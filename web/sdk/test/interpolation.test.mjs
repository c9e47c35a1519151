// Snapshot interpolation (buffer delay, jitter adaptation, bounded extrapolation, wrapping)
// and the smoothing of prediction corrections (snap above 2 m, blend below).
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { sdk } from './helpers.mjs';

const body = (id, x, vx = 0, y = 0) => ({ id, owner: 0, x, y, vx, vy: 0, angle: 0, angularVelocity: 0 });
// 60 ticks/s, a snapshot every 3 ticks (20/s, 50 ms); a body moving 1 m per tick (60 m/s).
const tickRate = 60, interval = 50, latency = 30;
const at = (tick) => (tick * 1000) / tickRate + latency;

test('the buffer draws two snapshot intervals behind the newest, interpolating exactly', () => {
  const interp = new sdk.Interpolator({ interval, tickRate });
  for (let tick = 0; tick <= 30; tick += 3) interp.push(tick, [body(7, tick, 60)], at(tick));
  assert.equal(interp.delay, 100);
  assert.equal(interp.jitter, 0);
  // Rendering when tick 30 arrived: server time 500 − 100 ms = tick 24; 10 ms later, tick 24.6.
  let s = interp.sample(at(30));
  assert.equal(s.extrapolated, 0);
  assert.ok(Math.abs(s.bodies[0].x - 24) < 1e-9, `x ${s.bodies[0].x}`);
  s = interp.sample(at(30) + 10);
  assert.ok(Math.abs(s.bodies[0].x - 24.6) < 1e-9, `x ${s.bodies[0].x}`);
});

test('jitter grows the delay beyond two intervals, at most 10 % of real time at once', () => {
  const interp = new sdk.Interpolator({ interval, tickRate });
  for (let tick = 0, i = 0; tick <= 300; tick += 3, ++i) interp.push(tick, [body(1, tick)], at(tick) + (i % 2 ? 40 : 0));
  assert.ok(interp.jitter > 30, `jitter ${interp.jitter}`);
  const target = interp.targetDelay();
  assert.ok(target > 2 * interval + 50, `target delay ${target}`);
  interp.sample(at(300));
  interp.sample(at(300) + 100);
  assert.ok(Math.abs(interp.delay - (100 + 10)) < 1e-9, `after 100 ms the delay moved by 10 ms: ${interp.delay}`);
  for (let t = 200; t <= 5000; t += 100) interp.sample(at(300) + t);
  assert.equal(interp.delay, target);

  // The jitter settles once arrivals are regular again, and so does the delay.
  for (let tick = 303; tick <= 900; tick += 3) interp.push(tick, [body(1, tick)], at(tick));
  assert.ok(interp.targetDelay() < target, `${interp.targetDelay()} < ${target}`);
});

test('past the newest snapshot bodies move on along their velocity for at most maxExtrapolation', () => {
  const interp = new sdk.Interpolator({ interval, tickRate });
  for (let tick = 0; tick <= 30; tick += 3) interp.push(tick, [body(3, tick, 60)], at(tick));
  let s = interp.sample(at(30) + 120);  // 20 ms past tick 30
  assert.ok(Math.abs(s.extrapolated - 20) < 1e-9);
  assert.ok(Math.abs(s.bodies[0].x - (30 + 60 * 0.02)) < 1e-9, `x ${s.bodies[0].x}`);
  s = interp.sample(at(30) + 2000);  // long after: held at one interval's extrapolation
  assert.equal(s.extrapolated, interval);
  assert.ok(Math.abs(s.bodies[0].x - (30 + 60 * 0.05)) < 1e-9, `x ${s.bodies[0].x}`);
});

test('in a wrapping world a body crossing the edge interpolates the short way round', () => {
  const interp = new sdk.Interpolator({ interval, tickRate, wrap: { width: 400, height: 400 } });
  interp.push(0, [body(1, 399)], at(0));
  interp.push(3, [body(1, 1)], at(3));
  interp.push(6, [body(1, 3)], at(6));
  const s = interp.sample(at(0) + 100 + 25);  // 100 ms behind: halfway between ticks 0 and 3
  assert.ok(Math.abs(s.bodies[0].x - 0) < 1e-9 || Math.abs(s.bodies[0].x - 400) < 1e-9, `x ${s.bodies[0].x}`);
});

test('a correction below 2 m is blended out, one above snaps', () => {
  const smoother = new sdk.CorrectionSmoother({ halfLife: 60 });
  const pose = { x: 10, y: 10, angle: 0 };
  smoother.correct({ x: 10.5, y: 10, angle: 0 }, pose);
  assert.equal(smoother.blends, 1);
  let drawn = smoother.apply(pose, 0);
  assert.ok(Math.abs(drawn.x - 10.5) < 1e-9, 'drawn where it was');
  drawn = smoother.apply(pose, 60);
  assert.ok(Math.abs(drawn.x - 10.25) < 1e-9, `half gone after the half-life: ${drawn.x}`);
  drawn = smoother.apply(pose, 1000);
  assert.ok(Math.abs(drawn.x - 10) < 1e-4);

  smoother.correct({ x: 13, y: 10, angle: 0 }, pose);
  assert.equal(smoother.snaps, 1);
  assert.equal(smoother.offset, 0);
  assert.equal(smoother.apply(pose, 1001).x, 10);
});
