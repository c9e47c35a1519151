// The hits this player sees: one of its bullets, as the page draws it, touching a target as the
// page draws it. Each is flashed at once (the local, predicted flash: white and brief), before
// the server's verdict arrives as a confirmed hit marker (draw.ts HitMarker). The page draws the
// others as they were a round trip and an interpolation delay ago, and the server judges a shot
// against that same past (docs/LAG_COMPENSATION.md): with compensation on, what flashes here is
// what the server confirms. Bots count their claims the same way (client_sim/hit_registration.hpp).
import { shortest } from './arena-sdk.mjs';
import type { Body, Flash, World } from './draw.js';

const CLAIM_FLASH_MS = 250;
const CLAIM_COLOUR = '#ffffff';

/** The circle around a shape (m): its vertices' farthest from the centre plus its skin radius,
 *  as the server's hit history keeps a target. */
export function boundingRadius(body: Body): number {
  const shape = body.shape;
  if (!shape) return 1;
  let core2 = 0;
  for (let i = 0; i + 1 < shape.vertices.length; i += 2) core2 = Math.max(core2, shape.vertices[i] ** 2 + shape.vertices[i + 1] ** 2);
  return Math.sqrt(core2) + shape.radius;
}

/** An own bullet where the prediction has it now, by the input that fired it. */
export interface OwnShot {
  sequence: number;
  x: number;
  y: number;
}

export class ShotClaims {
  /** Hits claimed since the page joined. */
  claimed = 0;
  private readonly claimedShots = new Set<number>();
  // A target is claimed once: the first bullet to reach it takes it (a rock splits, a ship is
  // lost), though the next may touch it as drawn before the verdict removes it.
  private readonly claimedTargets = new Set<number>();

  /** Looks at one drawn frame: each own bullet (of `bulletRadius` m) that touches one of
   *  `targets` (the other bodies as drawn) claims a hit on it, once. Returns the flashes of this
   *  frame's new claims. */
  frame(world: World, bullets: OwnShot[], bulletRadius: number, targets: Body[], now: number): Flash[] {
    const flashes: Flash[] = [];
    const way = (d: number, size: number) => (world.wraps && size > 0 ? shortest(d, size) : d);
    const reaches = bullets.length > 0 ? targets.map((t) => bulletRadius + boundingRadius(t)) : [];
    for (const bullet of bullets) {
      if (this.claimedShots.has(bullet.sequence)) continue;
      for (let k = 0; k < targets.length; ++k) {
        const t = targets[k];
        if (this.claimedTargets.has(t.id)) continue;
        const dx = way(t.x - bullet.x, world.width);
        const dy = way(t.y - bullet.y, world.height);
        const r = reaches[k];
        if (dx * dx + dy * dy > r * r) continue;
        this.claimedShots.add(bullet.sequence);
        this.claimedTargets.add(t.id);
        ++this.claimed;
        flashes.push({ x: bullet.x, y: bullet.y, born: now, life: CLAIM_FLASH_MS, radius: bulletRadius + 0.5, colour: CLAIM_COLOUR });
        break;
      }
    }
    // Shots and targets gone are forgotten: sequences and body ids only grow.
    if (this.claimedShots.size > 4 * bullets.length + 64) {
      const live = new Set(bullets.map((b) => b.sequence));
      for (const s of this.claimedShots) if (!live.has(s)) this.claimedShots.delete(s);
    }
    if (this.claimedTargets.size > 4 * targets.length + 64) {
      const live = new Set(targets.map((t) => t.id));
      for (const id of this.claimedTargets) if (!live.has(id)) this.claimedTargets.delete(id);
    }
    return flashes;
  }
}
