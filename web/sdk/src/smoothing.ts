// Corrections of the own prediction, smoothed: when a snapshot moves the predicted body (the
// server saw a collision the client could not), the drawn body keeps where it was and the
// difference fades out, unless it is larger than `snapDistance`, which is not an error to hide
// but a teleport (a respawn, a wrap, a long stall): then it snaps.
import { shortest, wrapAngle } from './interpolation.js';

export interface SmoothingOptions {
  /** m: a correction larger than this snaps (2). */
  snapDistance?: number;
  /** ms for the remaining offset to halve (60). */
  halfLife?: number;
  wrap?: { width: number; height: number };
}

export class CorrectionSmoother {
  private dx = 0;
  private dy = 0;
  private da = 0;
  private lastTime: number | null = null;
  private readonly snapDistance: number;
  private readonly halfLife: number;
  private readonly wrap?: { width: number; height: number };
  /** How many corrections snapped, and were blended. */
  snaps = 0;
  blends = 0;

  constructor(options: SmoothingOptions = {}) {
    this.snapDistance = options.snapDistance ?? 2;
    this.halfLife = options.halfLife ?? 60;
    this.wrap = options.wrap;
  }

  /** The prediction moved from `before` to `after` without an input: a correction. */
  correct(before: { x: number; y: number; angle: number }, after: { x: number; y: number; angle: number }): void {
    const ex = this.wrap ? shortest(before.x - after.x, this.wrap.width) : before.x - after.x;
    const ey = this.wrap ? shortest(before.y - after.y, this.wrap.height) : before.y - after.y;
    const nx = this.dx + ex;
    const ny = this.dy + ey;
    if (Math.hypot(nx, ny) > this.snapDistance) {
      this.dx = this.dy = this.da = 0;
      ++this.snaps;
      return;
    }
    if (ex === 0 && ey === 0 && before.angle === after.angle) return;
    this.dx = nx;
    this.dy = ny;
    this.da = wrapAngle(this.da + wrapAngle(before.angle - after.angle));
    ++this.blends;
  }

  /** What to draw at `time` (ms) for the predicted pose: the pose plus the fading offset. */
  apply<T extends { x: number; y: number; angle: number }>(pose: T, time: number): T {
    if (this.lastTime !== null) {
      const k = Math.pow(0.5, Math.max(0, time - this.lastTime) / this.halfLife);
      this.dx *= k;
      this.dy *= k;
      this.da *= k;
    }
    this.lastTime = time;
    return { ...pose, x: pose.x + this.dx, y: pose.y + this.dy, angle: wrapAngle(pose.angle + this.da) };
  }

  /** The offset drawn now, m. */
  get offset(): number {
    return Math.hypot(this.dx, this.dy);
  }
}
