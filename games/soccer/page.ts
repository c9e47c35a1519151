// Soccer's page module (web/page/src/game_page.ts): the pitch under the players and the ball,
// a green surface inside the walls, the halfway line, the centre circle and spot, and a goal
// area in front of each goal. Everything is placed from the walls the Welcome's world config
// holds (soccer_pitch.cpp: one static chain, each goal a pocket behind its line), so that the
// markings follow the pitch the server plays, whatever its size.
import type { ConfigBody, GamePage, GameView, WorldConfig } from '../../web/page/src/game_page.js';

/** The pitch, m: [left, right] × [bottom, top], the goals' mouths from goalLow to goalHigh. */
export interface Pitch {
  left: number;
  right: number;
  bottom: number;
  top: number;
  goalLow: number;
  goalHigh: number;
  outline: [number, number][];
}

/** The pitch the walls of `config` enclose, or null if it has no unrotated static chain with a
 *  goal pocket at each end (soccer_pitch.cpp builds one). The pockets are the chain's furthest points left and right: the goal lines are
 *  the furthest the other points reach, the mouths the pockets' span. */
export function pitchOf(config: WorldConfig): Pitch | null {
  const walls = (config.bodies ?? []).find((b: ConfigBody) => b.static && b.shape.type === 'chain');
  const points = walls?.shape.points ?? [];
  if (points.length < 4 || (walls?.angle ?? 0) !== 0) return null;
  const [px, py] = walls?.position ?? [0, 0];
  const at: [number, number][] = points.map(([x, y]) => [x + px, y + py]);
  const xs = at.map((p) => p[0]);
  const ys = at.map((p) => p[1]);
  const minX = Math.min(...xs);
  const maxX = Math.max(...xs);
  const inside = xs.filter((x) => x > minX && x < maxX);
  const pocket = at.filter((p) => p[0] === minX).map((p) => p[1]);
  const otherPocket = at.filter((p) => p[0] === maxX);
  if (inside.length === 0 || pocket.length < 2 || otherPocket.length < 2) return null;
  const pitch = {
    left: Math.min(...inside),
    right: Math.max(...inside),
    bottom: Math.min(...ys),
    top: Math.max(...ys),
    goalLow: Math.min(...pocket),
    goalHigh: Math.max(...pocket),
    outline: at,
  };
  return pitch.left < pitch.right && pitch.goalLow < pitch.goalHigh ? pitch : null;
}

// The markings' proportions: a goal area as deep as half the goal is wide, reaching that far
// past each post; a centre circle whose radius is a fifth of the pitch's width (touchline to
// touchline). The pitch is much narrower than a real one for its goals: FIFA's ratios would
// make the markings overlap.
const LINE = 'rgba(230, 240, 230, 0.55)';
const SURFACE = '#0d2a17';

// The pitch of the config drawn last: the config is the same object all match long.
let cached: { config: WorldConfig; pitch: Pitch | null } | null = null;

function drawPitch(g: CanvasRenderingContext2D, view: GameView): void {
  if (cached?.config !== view.config) cached = { config: view.config, pitch: pitchOf(view.config) };
  const p = cached.pitch;
  if (!p) return;
  const s = view.scale;
  const path = (points: [number, number][], close: boolean) => {
    g.beginPath();
    points.forEach(([x, y], i) => {
      const [sx, sy] = view.toScreen(x, y);
      if (i === 0) g.moveTo(sx, sy);
      else g.lineTo(sx, sy);
    });
    if (close) g.closePath();
  };
  path(p.outline, true);
  g.fillStyle = SURFACE;
  g.fill();

  g.strokeStyle = LINE;
  g.fillStyle = LINE;
  g.lineWidth = Math.max(2, 0.15 * s);
  const midX = (p.left + p.right) / 2;
  const midY = (p.bottom + p.top) / 2;
  path([[midX, p.bottom], [midX, p.top]], false);
  g.stroke();
  const [cx, cy] = view.toScreen(midX, midY);
  g.beginPath();
  g.arc(cx, cy, ((p.top - p.bottom) / 5) * s, 0, 2 * Math.PI);
  g.stroke();
  g.beginPath();
  g.arc(cx, cy, Math.max(2, 0.3 * s), 0, 2 * Math.PI);
  g.fill();

  const half = (p.goalHigh - p.goalLow) / 2;
  const low = Math.max(p.bottom, p.goalLow - half);
  const high = Math.min(p.top, p.goalHigh + half);
  for (const [line, inward] of [[p.left, half], [p.right, -half]]) {
    path([[line, low], [line + inward, low], [line + inward, high], [line, high]], false);
    g.stroke();
  }
}

export const page: GamePage = { drawBackground: drawPitch };
