// A game's own drawing on the page: its page module. The page draws every game from its
// manifest (game.ts, draw.ts); a game that wants more (soccer's pitch markings) adds
// games/NAME/page.ts exporting
//
//   export const page: GamePage = { drawBackground(g, view) { ... } };
//
// The page's build bundles the module of every game arena_game() registered that has one
// (web/page/CMakeLists.txt writes the table, `@arena/game-pages`), and the page calls the
// module whose name is the game's (the manifest's name, else the world config's "rules").
// A page built before a game existed has no module for it and draws it from its manifest.

import type { World } from './draw.js';
import type { Manifest } from './game.js';

/** A body of the world config, as `--config` files write it (docs/WORLD.md); metres, radians. */
export interface ConfigBody {
  shape: {
    type: string; // circle, capsule, box, polygon, segment, chain
    radius?: number;
    half_extents?: [number, number];
    half_length?: number;
    points?: [number, number][];
  };
  position?: [number, number];
  angle?: number;
  static?: boolean;
}

/** The fields of the world config (Welcome.world_config, the server's own JSON) that a page
 *  module is likely to read; every other field is there too. */
export interface WorldConfig {
  size?: [number, number];
  bodies?: ConfigBody[];
  rules?: string;
  /** The game's parameters (docs/GAMES.md, "Parameters"), as the server validated them. */
  rules_params?: Record<string, unknown>;
  [field: string]: unknown;
}

/** What a module draws with, each frame. */
export interface GameView {
  /** The world config the Welcome carried; the same object every frame of a match. */
  readonly config: WorldConfig;
  readonly world: World;
  /** The game's manifest (teams and their colours...); null if it declares none. */
  readonly game: Manifest | null;
  /** Canvas pixels per metre. */
  readonly scale: number;
  /** Canvas pixels of a world point: y is up in the world and down on the canvas, and a
   *  wrapping world is drawn the short way round from the camera. */
  toScreen(x: number, y: number): [number, number];
  /** The frame's time, ms (requestAnimationFrame's clock). */
  readonly now: number;
}

/** A game's page module. Both calls are optional; each gets the context in canvas pixels with
 *  its state saved and restored around the call, so a module may change any of it. */
export interface GamePage {
  /** Under the static bodies and the bodies, over the background grid: the field. */
  drawBackground?(g: CanvasRenderingContext2D, view: GameView): void;
  /** Over the bodies and the flashes. */
  drawForeground?(g: CanvasRenderingContext2D, view: GameView): void;
}

/** The module for a game: by the manifest's name, else by the config's rules; null for none. */
export function findGamePage(pages: ReadonlyMap<string, GamePage>, game: Manifest | null, config: WorldConfig): { name: string; page: GamePage } | null {
  for (const name of [game?.name, config.rules]) {
    const page = name ? pages.get(name) : undefined;
    if (name && page) return { name, page };
  }
  return null;
}

/** The Welcome's world config as an object ({} if it is not one: the core verified it, so that
 *  would be a bug, and the page still draws the game from its manifest). */
export function readWorldConfig(text: string): WorldConfig {
  try {
    const v: unknown = JSON.parse(text);
    return typeof v === 'object' && v !== null && !Array.isArray(v) ? (v as WorldConfig) : {};
  } catch {
    return {};
  }
}
