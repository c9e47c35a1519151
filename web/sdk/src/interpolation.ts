// Snapshot interpolation for the bodies a client does not predict. Snapshots are placed on the
// server's timeline (tick / tick_rate) and drawn `delay` behind the newest one the network
// could have brought: the buffer is at least two snapshot intervals (one to have a pair to
// interpolate between, one for a late or lost packet; Fiedler's "Snapshot Interpolation" asks
// three intervals for 5 % loss) and grows with the measured jitter (as Unity's adaptive
// interpolation does), moving at most 10 % faster or slower than real time so that a change
// never shows as a jump. Past the newest snapshot bodies are extrapolated along their velocity,
// for at most `maxExtrapolation`, then held.
import type { BodyState } from './core.js';

export interface InterpolationOptions {
  /** Snapshot interval in ms (1000 / Welcome.snapshot_rate). */
  interval: number;
  /** Ticks per second (Welcome.tick_rate): snapshot times are tick / tickRate. */
  tickRate: number;
  /** The least delay, in snapshot intervals (2). */
  minIntervals?: number;
  /** How many jitters (mean deviation of arrival) the delay adds above one interval (4). */
  jitterFactor?: number;
  /** The longest extrapolation past the newest snapshot, ms (one interval). */
  maxExtrapolation?: number;
  /** A world whose edges wrap: positions interpolate the short way round. */
  wrap?: { width: number; height: number };
  /** Snapshots kept (32). */
  capacity?: number;
}

interface Entry {
  time: number;  // server time of the snapshot, ms
  bodies: Map<number, BodyState>;
}

export interface Sampled {
  bodies: BodyState[];
  /** The server time drawn, ms. */
  serverTime: number;
  /** ms extrapolated past the newest snapshot (0 when interpolating). */
  extrapolated: number;
  /** The server time of the world drawn, ms: serverTime held to the buffer (the oldest
   *  snapshot before it, the newest plus the extrapolation past it); 0 with no snapshot. */
  moment: number;
}

export class Interpolator {
  private readonly o: Required<Omit<InterpolationOptions, 'wrap'>> & { wrap?: { width: number; height: number } };
  private readonly entries: Entry[] = [];
  // The smallest (arrival − server time) seen lately: the fastest trip, the clock offset.
  private offsets: number[] = [];
  private jitterValue = 0;  // mean deviation of each arrival from the fastest trip, ms (EWMA)
  private lastTransit: number | null = null;
  private delayValue: number;
  private lastRender: number | null = null;

  constructor(options: InterpolationOptions) {
    this.o = {
      minIntervals: 2,
      jitterFactor: 4,
      maxExtrapolation: options.interval,
      capacity: 32,
      ...options,
    };
    this.delayValue = this.o.minIntervals * this.o.interval;
  }

  /** A snapshot's bodies, arrived at local time `arrival` (ms, the clock stateAt is given). */
  push(tick: number, bodies: BodyState[], arrival: number): void {
    const time = (tick * 1000) / this.o.tickRate;
    const newest = this.entries[this.entries.length - 1];
    if (newest && time <= newest.time) return;  // a duplicate or older: nothing new
    this.entries.push({ time, bodies: new Map(bodies.map((b) => [b.id, b])) });
    if (this.entries.length > this.o.capacity) this.entries.shift();

    const transit = arrival - time;
    this.offsets.push(transit);
    if (this.offsets.length > 64) this.offsets.shift();
    // RFC 3550's interarrival jitter: the change in transit time between consecutive packets.
    if (this.lastTransit !== null) this.jitterValue += (Math.abs(transit - this.lastTransit) - this.jitterValue) / 16;
    this.lastTransit = transit;
  }

  /** The delay the buffer aims at now, ms: at least minIntervals intervals, more with jitter. */
  targetDelay(): number {
    return Math.max(this.o.minIntervals * this.o.interval, this.o.interval + this.o.jitterFactor * this.jitterValue);
  }
  /** The delay in use (it moves towards targetDelay at ±10 % of real time). */
  get delay(): number {
    return this.delayValue;
  }
  get jitter(): number {
    return this.jitterValue;
  }
  get size(): number {
    return this.entries.length;
  }

  /** The bodies to draw at local time `renderTime` (ms). */
  sample(renderTime: number): Sampled {
    if (this.lastRender !== null) {
      const dt = Math.max(0, renderTime - this.lastRender);
      const step = Math.min(Math.abs(this.targetDelay() - this.delayValue), 0.1 * dt);
      this.delayValue += Math.sign(this.targetDelay() - this.delayValue) * step;
    }
    this.lastRender = renderTime;
    if (this.entries.length === 0) return { bodies: [], serverTime: 0, extrapolated: 0, moment: 0 };
    const offset = Math.min(...this.offsets);
    const t = renderTime - offset - this.delayValue;

    const first = this.entries[0];
    const newest = this.entries[this.entries.length - 1];
    if (t <= first.time) return { bodies: [...first.bodies.values()], serverTime: t, extrapolated: 0, moment: first.time };
    if (t >= newest.time) {
      const ahead = Math.min(t - newest.time, this.o.maxExtrapolation);
      const s = ahead / 1000;
      const bodies = [...newest.bodies.values()].map((b) =>
        this.wrapped({ ...b, x: b.x + b.vx * s, y: b.y + b.vy * s, angle: wrapAngle(b.angle + b.angularVelocity * s) }),
      );
      return { bodies, serverTime: t, extrapolated: ahead, moment: newest.time + ahead };
    }
    let i = this.entries.length - 2;
    while (this.entries[i].time > t) --i;
    const a = this.entries[i];
    const b = this.entries[i + 1];
    const f = (t - a.time) / (b.time - a.time);
    const bodies: BodyState[] = [];
    for (const to of b.bodies.values()) {
      const from = a.bodies.get(to.id);
      bodies.push(from ? this.lerp(from, to, f) : to);  // a body that just came into view: as it came
    }
    return { bodies, serverTime: t, extrapolated: 0, moment: t };
  }

  private lerp(a: BodyState, b: BodyState, f: number): BodyState {
    const w = this.o.wrap;
    const dx = w ? shortest(b.x - a.x, w.width) : b.x - a.x;
    const dy = w ? shortest(b.y - a.y, w.height) : b.y - a.y;
    return this.wrapped({
      id: b.id,
      owner: b.owner,
      x: a.x + dx * f,
      y: a.y + dy * f,
      vx: a.vx + (b.vx - a.vx) * f,
      vy: a.vy + (b.vy - a.vy) * f,
      angle: wrapAngle(a.angle + shortest(b.angle - a.angle, 2 * Math.PI) * f),
      angularVelocity: a.angularVelocity + (b.angularVelocity - a.angularVelocity) * f,
    });
  }

  private wrapped(b: BodyState): BodyState {
    const w = this.o.wrap;
    if (!w) return b;
    return { ...b, x: modulo(b.x, w.width), y: modulo(b.y, w.height) };
  }
}

/** d reduced to (−period/2, period/2]: the short way round. */
export function shortest(d: number, period: number): number {
  return d - period * Math.round(d / period);
}
export function wrapAngle(a: number): number {
  return shortest(a, 2 * Math.PI);
}
function modulo(v: number, m: number): number {
  return ((v % m) + m) % m;
}
