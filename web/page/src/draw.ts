// Draws one frame of the game on a 2D canvas: every body by its game kind and its shape (the
// vertices the server sent, in the body's frame), centred on the own ship, y up, and the short
// way round a wrapping world so that bodies across the seam show beside the ship. A game's page
// module (game_page.ts), if it has one, draws under the bodies and over them.
import type { GamePage, GameView, WorldConfig } from './game_page.js';

export interface Shape {
  /** The body's id (the SDK's; a static's is its body's). */
  id?: number;
  kind: number;
  type: number; // circle 0, capsule 1, polygon 2, segment 3
  radius: number;
  vertices: number[];
}
export interface Body {
  id: number;
  owner: number;
  x: number;
  y: number;
  angle: number;
  kind: number;
  predicted: boolean;
  shape?: Shape;
}
export interface StaticBody {
  x: number;
  y: number;
  angle: number;
  shape: Shape;
}
export interface World {
  wraps: boolean;
  width: number;
  height: number;
}
/** A flash where something happened, drawn for `life` ms. */
export interface Flash {
  x: number;
  y: number;
  born: number;
  life: number;
  radius: number;
  colour: string;
}

/** A hit of this player's that the server confirmed (a GameEvent), drawn for `life` ms as a
 *  magenta X in a dashed ring at the target: unlike the flashes, which show what happened to
 *  whomever, it says "your shot counted". */
export interface HitMarker {
  x: number;
  y: number;
  born: number;
  life: number;
  /** The target's radius, m. */
  radius: number;
}

/** ?debug=lag: one shot's targets as the view its input carried showed them (what the server
 *  rewinds to), drawn as outlined circles fading over `life` ms; or, `judged`, the hitbox the
 *  server hit when it judged the shot in the past (Asteroids' `judged_in_past` event), drawn
 *  dashed in amber. */
export interface LagShot {
  born: number;
  life: number;
  targets: { x: number; y: number; radius: number }[];
  judged?: boolean;
}

export const HIT_COLOUR = '#ff3df2';
export const LAG_COLOUR = '#4dff9a';
/** ?debug=lag: the hitbox the server judged a shot against. */
export const JUDGED_COLOUR = '#ffb020';

// The kinds a server that sends no manifest means (Asteroids' before manifests); a game's own
// tags come from its manifest (setTags).
export const KIND_SHIP = 1;
export const KIND_ROCK = 2;
export const KIND_BULLET = 3;

/** How to draw a kind of body (Welcome.game.body_tags). colour 'team': its owner's team colour. */
export interface Tag {
  kind: number;
  style: string; // 'ship', 'disc' or '' (the shape)
  colour: string;
}

/** Metres shown across the canvas's shorter side, around the own ship. */
export const VIEW_METRES = 90;

export class Painter {
  private readonly g: CanvasRenderingContext2D;
  private scale = 1;
  private cx = 0;
  private cy = 0;
  private world: World = { wraps: false, width: 0, height: 0 };
  private player = 0;
  private tags: Map<number, Tag> | null = null;
  private ownerColour: (owner: number) => string | null = () => null;
  private gamePage: GamePage | null = null;
  private gameConfig: WorldConfig = {};
  private gameManifest: GameView['game'] = null;
  /** Frames the game's page module drew (either call), for tests and the console. */
  gamePageFrames = 0;

  constructor(private readonly canvas: HTMLCanvasElement) {
    const g = canvas.getContext('2d');
    if (!g) throw new Error('no 2D canvas in this browser');
    this.g = g;
  }

  /** The game's body tags (null: the kinds of before), and the colour of an owner's team. */
  setTags(tags: Tag[] | null, ownerColour: (owner: number) => string | null): void {
    this.tags = tags ? new Map(tags.map((t) => [t.kind, t])) : null;
    this.ownerColour = ownerColour;
  }

  /** The game's page module and what it draws from (null: none, every body from its tag). */
  setGamePage(page: GamePage | null, config: WorldConfig, game: GameView['game']): void {
    this.gamePage = page;
    this.gameConfig = config;
    this.gameManifest = game;
  }

  /** `player`: the own player's id; its ship is drawn in gold, predicted or not. `span`: metres
   *  across the canvas's shorter side (a spectator sees the whole world). */
  /** `hits`: the confirmed hits' markers; `lagShots`: ?debug=lag's overlay. Returns the overlay's
   *  shapes drawn. */
  frame(world: World, player: number, centre: { x: number; y: number }, statics: StaticBody[], bodies: Body[], flashes: Flash[], now: number,
    span = VIEW_METRES, hits: HitMarker[] = [], lagShots: LagShot[] = []): number {
    const { canvas, g } = this;
    const dpr = window.devicePixelRatio || 1;
    const w = Math.round(canvas.clientWidth * dpr);
    const h = Math.round(canvas.clientHeight * dpr);
    if (canvas.width !== w || canvas.height !== h) {
      canvas.width = w;
      canvas.height = h;
    }
    this.world = world;
    this.player = player;
    this.scale = Math.min(w, h) / span;
    this.cx = centre.x;
    this.cy = centre.y;
    g.setTransform(1, 0, 0, 1, 0, 0);
    g.fillStyle = '#05070d';
    g.fillRect(0, 0, w, h);
    this.grid(w, h);
    const view: GameView | null = this.gamePage && {
      config: this.gameConfig,
      world,
      game: this.gameManifest,
      scale: this.scale,
      toScreen: (x: number, y: number) => this.toScreen(x, y),
      now,
    };
    const drewBackground = view !== null && this.callGamePage('drawBackground', view);
    for (const s of statics) this.body(s.x, s.y, s.angle, s.shape, '#556', '#334');
    for (const b of bodies) this.drawBody(b);
    for (const f of flashes) this.flash(f, now);
    let lagShapes = 0;
    for (const s of lagShots) lagShapes += this.lagShot(s, now);
    for (const m of hits) this.hitMarker(m, now);
    const drewForeground = view !== null && this.callGamePage('drawForeground', view);
    if (drewBackground || drewForeground) ++this.gamePageFrames;
    return lagShapes;
  }

  /** A confirmed hit: an X across the target in a dashed ring, closing onto it as it fades. */
  private hitMarker(m: HitMarker, now: number): void {
    const t = (now - m.born) / m.life;
    if (t < 0 || t > 1) return;
    const { g } = this;
    const [sx, sy] = this.toScreen(m.x, m.y);
    const r = Math.max(6, (m.radius + 1.5) * (1.4 - 0.6 * t) * this.scale);
    g.save();
    g.globalAlpha = 1 - t * t;
    g.strokeStyle = HIT_COLOUR;
    g.lineWidth = Math.max(2, this.scale * 0.35);
    g.lineCap = 'round';
    g.beginPath();
    const d = r * 0.7;
    g.moveTo(sx - d, sy - d);
    g.lineTo(sx + d, sy + d);
    g.moveTo(sx + d, sy - d);
    g.lineTo(sx - d, sy + d);
    g.stroke();
    g.setLineDash([4, 4]);
    g.beginPath();
    g.arc(sx, sy, r, 0, 2 * Math.PI);
    g.stroke();
    g.restore();
  }

  /** ?debug=lag: a shot's targets as the view it carried had them, or the hitbox the server
   *  judged, outlined; how many drawn. */
  private lagShot(s: LagShot, now: number): number {
    const t = (now - s.born) / s.life;
    if (t < 0 || t > 1) return 0;
    const { g } = this;
    g.save();
    g.globalAlpha = 1 - t;
    g.strokeStyle = s.judged ? JUDGED_COLOUR : LAG_COLOUR;
    g.lineWidth = Math.max(1, this.scale * 0.12);
    if (s.judged) g.setLineDash([4, 3]);
    for (const b of s.targets) {
      const [sx, sy] = this.toScreen(b.x, b.y);
      g.beginPath();
      g.arc(sx, sy, Math.max(2, b.radius * this.scale), 0, 2 * Math.PI);
      g.stroke();
    }
    g.restore();
    return s.targets.length;
  }

  /** Runs one call of the game's page module, if it has it; whether it ran. A module that
   *  throws is dropped, told once on the console: the page goes on drawing the game from its
   *  manifest rather than stop drawing (an exception here would end the frame loop). */
  private callGamePage(call: 'drawBackground' | 'drawForeground', view: GameView): boolean {
    const draw = this.gamePage?.[call];
    if (!draw) return false;
    this.g.save();
    try {
      draw.call(this.gamePage, this.g, view);
      return true;
    } catch (e) {
      console.error(`the game's page module failed in ${call}, drawn without it from now on:`, e);
      this.gamePage = null;
      return false;
    } finally {
      this.g.restore();
    }
  }

  /** Canvas pixels of a world point, relative to the centre (the short way when wrapping). */
  private toScreen(x: number, y: number): [number, number] {
    let dx = x - this.cx;
    let dy = y - this.cy;
    if (this.world.wraps) {
      dx -= Math.round(dx / this.world.width) * this.world.width;
      dy -= Math.round(dy / this.world.height) * this.world.height;
    }
    return [this.canvas.width / 2 + dx * this.scale, this.canvas.height / 2 - dy * this.scale];
  }

  private grid(w: number, h: number): void {
    const { g } = this;
    const step = 10;
    g.strokeStyle = '#111826';
    g.lineWidth = 1;
    g.beginPath();
    const x0 = Math.floor((this.cx - w / 2 / this.scale) / step) * step;
    const y0 = Math.floor((this.cy - h / 2 / this.scale) / step) * step;
    for (let x = x0; x < this.cx + w / 2 / this.scale + step; x += step) {
      const sx = w / 2 + (x - this.cx) * this.scale;
      g.moveTo(sx, 0);
      g.lineTo(sx, h);
    }
    for (let y = y0; y < this.cy + h / 2 / this.scale + step; y += step) {
      const sy = h / 2 - (y - this.cy) * this.scale;
      g.moveTo(0, sy);
      g.lineTo(w, sy);
    }
    g.stroke();
  }

  private drawBody(b: Body): void {
    if (this.tags) return this.drawTagged(b, this.tags.get(b.kind));
    if (b.kind === KIND_SHIP) return this.ship(b);
    if (b.kind === KIND_BULLET) return this.dot(b, b.shape?.radius ?? 0.2, '#ffe27a');
    if (b.shape) return this.body(b.x, b.y, b.angle, b.shape, b.kind === KIND_ROCK ? '#2a2f3a' : '#333', '#9aa3b5');
    this.dot(b, 1, '#888');
  }

  /** A body as its game's tag says: a ship, a disc or its shape, in its colour. */
  private drawTagged(b: Body, tag: Tag | undefined): void {
    const colour = tag?.colour === 'team' ? this.ownerColour(b.owner) : tag?.colour || null;
    if (tag?.style === 'ship') return this.ship(b, colour);
    if (tag?.style === 'disc') return this.dot(b, b.shape?.radius ?? 0.2, colour ?? '#ffe27a');
    if (b.shape) return this.body(b.x, b.y, b.angle, b.shape, colour ?? '#2a2f3a', '#9aa3b5');
    this.dot(b, 1, colour ?? '#888');
  }

  /** A ship: an arrowhead pointing along its facing, inside its collision circle; the own one
   *  gold, the others `colour` (their team's) or blue. */
  private ship(b: Body, colour: string | null = null): void {
    const { g } = this;
    const [sx, sy] = this.toScreen(b.x, b.y);
    const r = (b.shape?.radius ?? 1.5) * this.scale;
    g.save();
    g.translate(sx, sy);
    g.rotate(-b.angle);
    g.beginPath();
    g.moveTo(r, 0);
    g.lineTo(-r * 0.8, r * 0.7);
    g.lineTo(-r * 0.45, 0);
    g.lineTo(-r * 0.8, -r * 0.7);
    g.closePath();
    const mine = b.predicted || b.owner === this.player;
    g.fillStyle = colour ?? (mine ? '#ffcf33' : '#5ec8ff');
    g.fill();
    g.strokeStyle = mine ? '#fff3c4' : '#d4f0ff';
    g.lineWidth = Math.max(1, this.scale * 0.12);
    g.stroke();
    g.restore();
  }

  private dot(b: Body, radius: number, colour: string): void {
    const { g } = this;
    const [sx, sy] = this.toScreen(b.x, b.y);
    g.beginPath();
    g.arc(sx, sy, Math.max(1.5, radius * this.scale), 0, 2 * Math.PI);
    g.fillStyle = colour;
    g.fill();
  }

  /** Any shape, from its vertices in the body's frame. */
  private body(x: number, y: number, angle: number, shape: Shape, fill: string, stroke: string): void {
    const { g } = this;
    const [sx, sy] = this.toScreen(x, y);
    const s = this.scale;
    g.save();
    g.translate(sx, sy);
    g.rotate(-angle);
    g.beginPath();
    const v = shape.vertices;
    if (shape.type === 2 && v.length >= 6) {
      g.moveTo(v[0] * s, -v[1] * s);
      for (let i = 2; i + 1 < v.length; i += 2) g.lineTo(v[i] * s, -v[i + 1] * s);
      g.closePath();
    } else if ((shape.type === 1 || shape.type === 3) && v.length >= 4) {
      g.moveTo(v[0] * s, -v[1] * s);
      g.lineTo(v[2] * s, -v[3] * s);
      g.lineCap = 'round';
      g.lineWidth = Math.max(1, 2 * shape.radius * s);
      g.strokeStyle = stroke;
      g.stroke();
      g.restore();
      return;
    } else {
      g.arc(0, 0, Math.max(1, shape.radius * s), 0, 2 * Math.PI);
    }
    g.fillStyle = fill;
    g.fill();
    g.strokeStyle = stroke;
    g.lineWidth = Math.max(1, s * 0.15);
    g.stroke();
    g.restore();
  }

  private flash(f: Flash, now: number): void {
    const t = (now - f.born) / f.life;
    if (t < 0 || t > 1) return;
    const { g } = this;
    const [sx, sy] = this.toScreen(f.x, f.y);
    g.beginPath();
    g.arc(sx, sy, f.radius * (0.5 + 2 * t) * this.scale, 0, 2 * Math.PI);
    g.globalAlpha = 1 - t;
    g.strokeStyle = f.colour;
    g.lineWidth = Math.max(2, this.scale * 0.5);
    g.stroke();
    g.globalAlpha = 1;
  }
}
