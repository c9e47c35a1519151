// The page that plays Arena: joins the server it came from (ws://host/ws) with the name from
// ?name=, sends the keyboard's controls (the SDK sends them once per server tick), and draws
// what the SDK says to draw at each requestAnimationFrame: the own ship predicted with the
// server's world in WebAssembly, everything else interpolated from the snapshots. With
// ?spectate it watches instead: no ship, no controls, the whole world on the canvas.
// ?match=ID joins that match, ?mode=NAME joins or creates one of that mode, neither the
// server's default match; ?lobby shows the lobby (src/lobby.ts) instead of the game.
// window.arenaPage holds the client and the page's figures, for tests and the console.
// A game with a page module of its own (games/NAME/page.ts, game_page.ts) draws with it too.
// A hit of this player's that the server confirms (a GameEvent naming it as the shooter) shows
// as a magenta X at the target and "hit" under the centre, after the white flash the page
// shows the moment its own bullet touched the target as drawn (src/claims.ts); ?debug=lag
// draws, for the player's last shots, the targets as the view that shot's input carried showed
// them (the world the server rewinds to judge the shot), and dashed, for each of its hits
// judged in the past, the hitbox the server hit there (docs/LAG_COMPENSATION.md).
import { gamePages } from '@arena/game-pages';
import { connect } from './arena-sdk.mjs';
import type { ConnectOptions } from './arena-sdk.mjs';
import { ShotClaims, boundingRadius } from './claims.js';
import { BUTTON_FIRE, Controls } from './controls.js';
import { Body, Flash, HitMarker, KIND_BULLET, KIND_SHIP, LagShot, Painter, StaticBody, VIEW_METRES, World } from './draw.js';
import { Manifest, eventText, resultText, teamColour, teamField } from './game.js';
import { findGamePage, readWorldConfig } from './game_page.js';
import { Hud, Line } from './hud.js';
import { PageQuery, inviteLink, lobbyLink, readQuery } from './links.js';
import { LobbyState, newLobbyState, showLobby } from './lobby.js';

const FLASH_MS = 600;
const HIT_MS = 500;
/** ?debug=lag: the drawn views kept (about two seconds of frames at 60 a second: more than the
 *  server's 250 ms cap and any interpolation delay), the shots shown, and how long each shows. */
const LAG_VIEWS = 120;
const LAG_SHOTS = 6;
const LAG_MS = 1000;
/** ?debug=lag: while the fire button is held, a shot is shown at most this often (ms). */
const LAG_EVERY_MS = 200;
const SAMPLES = 4096;

function keep(samples: number[], value: number): void {
  if (samples.length >= SAMPLES) samples.shift();
  samples.push(value);
}

interface PageState {
  client: unknown;
  /** ?spectate: watching without a body. */
  spectating: boolean;
  /** Bodies drawn in the last frame. */
  drawn: number;
  playerId: number;
  entityId: number;
  /** The own body as the last snapshot from the server had it (not predicted). */
  serverOwn: { tick: number; x: number; y: number } | null;
  /** The last snapshot's bodies as the server sent them (id, owner, pose). */
  view: { tick: number; bodies: { id: number; owner: number; x: number; y: number }[] };
  snapshots: number;
  frames: number;
  fps: number;
  snapshotRate: number;
  predictionError: number | null;
  predictionErrorMax: number;
  /** The last SAMPLES prediction errors (m) and times from a snapshot's arrival to the first
   *  frame drawn after it (ms), for percentiles. */
  predictionErrors: number[];
  arrivalToRender: number[];
  events: number;
  /** Own shots drawn before any snapshot held them (the SDK's predicted shots), summed over
   *  the frames drawn. */
  predictedShotsDrawn: number;
  bye: unknown;
  error: string;
  /** The match joined and its mode (the Welcome's), and the link that invites another player
   *  into it; '' until the Welcome. */
  match: string;
  mode: string;
  invite: string;
  /** ?lobby: the lobby's matches and its last error; null on the game's page. */
  lobby: LobbyState | null;
  /** The game's manifest (Welcome.game), and its events as the page told them. */
  game: Manifest | null;
  records: { kind: number; values: number[]; text: string }[];
  /** The game's page module drawing the match ('' for none: the manifest alone) and the frames
   *  it drew. */
  gamePage: string;
  gamePageFrames: number;
  /** Hits of this player's the server confirmed (GameEvents: a rock_hit by it, a ship_destroyed
   *  with it as `other`), each drawn as a hit marker. */
  hitsConfirmed: number;
  /** Hits this player saw: its bullet touching a target as the page drew them (src/claims.ts),
   *  each flashed white at once, before any verdict. */
  hitsClaimed: number;
  /** ?debug=lag: whether it is on, the shots it showed, and the outlined targets it drew (summed
   *  over the frames, and in the last frame). */
  debugLag: boolean;
  lagShots: number;
  /** ?debug=lag: the hitboxes the server judged this player's shots against (Asteroids'
   *  `judged_in_past` events), each outlined dashed in amber. */
  lagJudged: number;
  lagShapesDrawn: number;
  lagShapes: number;
  /** The Welcome's tick rate (0 before it). */
  tickRate: number;
}

declare global {
  interface Window {
    arenaPage: PageState;
  }
}

function newPageState(spectating: boolean): PageState {
  return {
    client: null, spectating, drawn: 0, playerId: 0, entityId: 0, serverOwn: null, view: { tick: 0, bodies: [] }, snapshots: 0, frames: 0, fps: 0,
    snapshotRate: 0, predictionError: null, predictionErrorMax: 0, predictionErrors: [], arrivalToRender: [], events: 0, predictedShotsDrawn: 0,
    bye: null, error: '', match: '', mode: '', invite: '', lobby: null, game: null, records: [], gamePage: '', gamePageFrames: 0,
    hitsConfirmed: 0, hitsClaimed: 0, debugLag: false, lagShots: 0, lagJudged: 0, lagShapesDrawn: 0, lagShapes: 0, tickRate: 0,
  };
}

/** Where the query asks to go: a match by id, join-or-create by mode, else the default match. */
function destination(query: PageQuery): ConnectOptions {
  const options: ConnectOptions = { spectate: query.spectate };
  if (query.match) options.match = query.match;
  if (query.mode) options.mode = query.mode;
  return options;
}

function joiningText(query: PageQuery, name: string): string {
  const where = query.match ? ` match ${query.match}` : query.mode ? ` a match of mode ${query.mode}` : '';
  return query.spectate ? `joining${where} to watch as ${name}…` : `joining${where} as ${name}…`;
}

async function main(): Promise<void> {
  const query = readQuery(location.search);
  const page = newPageState(query.spectate && !query.lobby);
  page.debugLag = query.debugLag && !query.spectate;
  window.arenaPage = page;
  if (query.lobby) {
    page.lobby = newLobbyState();
    showLobby(page.lobby, query);
    return;
  }
  await play(page, query);
}

async function play(page: PageState, query: PageQuery): Promise<void> {
  const canvas = document.getElementById('game') as HTMLCanvasElement;
  const painter = new Painter(canvas);
  const hud = new Hud();
  const spectating = query.spectate;
  // A spectator has no controls: the keys do nothing (and scroll nothing away).
  const controls = spectating ? null : new Controls(window);
  const name = query.name || (spectating ? 'spectator' : 'player');

  hud.setStatus(joiningText(query, name));
  hud.lobby(lobbyLink(query.name, query.token));
  if (spectating) hud.spectating();
  const scheme = location.protocol === 'https:' ? 'wss:' : 'ws:';
  const client = await connect(`${scheme}//${location.host}/ws`, name, query.token, destination(query));
  page.client = client;

  let world: World = { wraps: false, width: 0, height: 0 };
  let statics: StaticBody[] = [];
  // The static bodies' ids (a static's shape id is its body's): snapshots hold them too, with no
  // shape of their own, and they are drawn from the Welcome's statics already (soccer's walls
  // would otherwise show as a 1 m disc at each segment's middle).
  let staticIds = new Set<number>();
  let flashes: Flash[] = [];
  let snapshotTimes: number[] = [];
  let frameTimes: number[] = [];
  let centre = { x: 0, y: 0 };
  let unrendered: number | null = null; // when the oldest snapshot not yet drawn arrived
  // Where each body was last drawn: a game event names a body, not a place.
  const lastSeen = new Map<number, { x: number; y: number; r: number }>();
  let hits: HitMarker[] = [];
  const claims = new ShotClaims();
  let bulletRadius = 0.1; // m, Asteroids' until a drawn bullet tells the game's
  // ?debug=lag: the last LAG_VIEWS views drawn, each with its moment (tick × 256 + fraction, as
  // the SDK tells the inputs) and the other bodies in it; the shots shown.
  const views: { moment: number; targets: { x: number; y: number; radius: number }[] }[] = [];
  let lagShots: LagShot[] = [];
  let lastLagShot = -Infinity;
  // The body kind of a bullet, which no shot aims at: the game's tag named "bullet", else
  // Asteroids' kind when the server declares no tags.
  const bulletKind = () => {
    const tags = page.game?.bodyTags ?? [];
    return tags.length === 0 ? KIND_BULLET : tags.find((t) => t.name === 'bullet')?.kind ?? -1;
  };
  // The Input.buttons bit that fires: the game's input named "fire" (Asteroids' bit 1), else
  // the page's space bar (BUTTON_FIRE) when the server declares no inputs.
  const fireMask = () => {
    const inputs = page.game?.inputs ?? [];
    if (inputs.length === 0) return BUTTON_FIRE;
    const fire = inputs.find((i) => i.name === 'fire');
    return fire ? 1 << fire.button : 0;
  };

  const lines = (): Line[] => [...client.players.values()];
  const nameOf = (player: number) => client.players.get(player)?.name || (player === 0 ? 'nobody' : `#${player}`);
  // A body's owner's team colour, from the game's declared team field.
  const ownerColour = (owner: number): string | null => {
    const game = page.game;
    const field = game ? teamField(game) : -1;
    return game && field >= 0 ? teamColour(game, client.values.get(owner)?.[field] ?? 0) : null;
  };
  client.on('welcome', (w: { playerId: number; entityId: number; world: World; statics: StaticBody[]; match: string; mode: string; game: Manifest | null; tickRate: number;
    worldConfig: string }) => {
    page.playerId = w.playerId;
    page.entityId = w.entityId;
    page.match = w.match;
    page.mode = w.mode;
    page.invite = inviteLink(w.match, location.href);
    hud.match(w.match, w.mode, page.invite);
    world = w.world;
    statics = w.statics;
    staticIds = new Set(statics.map((s) => s.shape.id ?? 0));
    page.game = w.game;
    page.tickRate = w.tickRate;
    hud.declare(w.game, w.tickRate);
    if (w.game) controls?.declare(w.game.inputs);
    painter.setTags(w.game?.bodyTags ?? null, ownerColour);
    const config = readWorldConfig(w.worldConfig);
    const module = findGamePage(gamePages, w.game, config);
    painter.setGamePage(module?.page ?? null, config, w.game);
    page.gamePage = module?.name ?? '';
    hud.setStatus('');
  });
  client.on('snapshot', (s: { tick: number; bodies: { id: number; owner: number; x: number; y: number }[]; predictionError: number | null }) => {
    ++page.snapshots;
    unrendered ??= performance.now();
    page.view = { tick: s.tick, bodies: s.bodies };
    snapshotTimes.push(performance.now());
    const own = s.bodies.find((b) => b.id === client.session.entityId);
    page.entityId = client.session.entityId;
    if (own) page.serverOwn = { tick: s.tick, x: own.x, y: own.y };
    if (s.predictionError !== null) {
      page.predictionError = s.predictionError;
      page.predictionErrorMax = Math.max(page.predictionErrorMax, s.predictionError);
      keep(page.predictionErrors, s.predictionError);
    }
  });
  client.on('players', () => hud.declared(page.playerId, lines(), client.values, client.teamValues));
  // The game's own events, told as its manifest says.
  client.on('record', (r: { kind: number; values: number[] }) => {
    ++page.events;
    if (!page.game) return;
    const text = eventText(page.game, r.kind, r.values, nameOf);
    page.records.push({ kind: r.kind, values: r.values, text });
    if (page.records.length > 256) page.records.shift();
    if (text) hud.flashStatus(text);
    // ?debug=lag: a shot of this player's judged in the past, with the hitbox the server hit.
    if (page.debugLag && page.game.events[r.kind]?.name === 'judged_in_past' && r.values[0] === page.playerId) {
      const [, x, y, radius] = r.values;
      lagShots.push({ born: performance.now(), life: LAG_MS, targets: [{ x: x / 1000, y: y / 1000, radius: radius / 1000 }], judged: true });
      if (lagShots.length > LAG_SHOTS) lagShots.shift();
      ++page.lagJudged;
    }
  });
  client.on('event', (e: { kind: number; body: number; player: number; other: number; size: number; value: number }) => {
    ++page.events;
    const at = lastSeen.get(e.body);
    const born = performance.now();
    // This player's hit, as the server judged it: a rock it shot, a ship it destroyed.
    const mine = !spectating && page.playerId !== 0 && ((e.kind === 0 && e.player === page.playerId) || (e.kind === 1 && e.other === page.playerId && e.player !== page.playerId));
    if (mine) {
      ++page.hitsConfirmed;
      hud.hitConfirmed(page.hitsConfirmed);
      if (at) hits.push({ x: at.x, y: at.y, born, life: HIT_MS, radius: at.r });
    }
    // rock_hit 0, ship_destroyed 1, respawn 2, wave 3, shot_rewound 4 (protocol GameEventKind).
    if (e.kind === 1 && at) flashes.push({ x: at.x, y: at.y, born, life: FLASH_MS * 2, radius: 3, colour: e.player === page.playerId ? '#ff5a4f' : '#ffa640' });
    else if (e.kind === 0 && at) flashes.push({ x: at.x, y: at.y, born, life: FLASH_MS, radius: at.r, colour: '#c9d3e6' });
    else if (e.kind === 3) hud.flashStatus(`wave ${e.size}`);
    else if (e.kind === 2 && e.player === page.playerId) hud.flashStatus('respawned');
    // Lag compensation: the shooter saw this player that long ago, and the hit was judged there.
    else if (e.kind === 4 && e.player === page.playerId && page.tickRate > 0) hud.flashStatus(`hit where you were ${Math.round((e.value * 1000) / (256 * page.tickRate))} ms ago`);
  });
  // ?debug=lag: an input with the fire button held going out shows its view's targets (the
  // view drawn at that moment: the one kept with that moment, else the nearest kept).
  if (page.debugLag) {
    client.on('input', (i: { buttons: number; tick: number; fraction: number }) => {
      if ((i.buttons & fireMask()) === 0 || views.length === 0) return;
      const born = performance.now();
      if (born - lastLagShot < LAG_EVERY_MS) return;
      lastLagShot = born;
      const moment = i.tick * 256 + i.fraction;
      let best = views[views.length - 1];
      for (const v of views) if (Math.abs(v.moment - moment) < Math.abs(best.moment - moment)) best = v;
      lagShots.push({ born, life: LAG_MS, targets: best.targets });
      if (lagShots.length > LAG_SHOTS) lagShots.shift();
      ++page.lagShots;
    });
  }
  client.on('bye', (b: { reason: string; matchOver: boolean; winner: number; scoreboard: Line[]; winningTeam?: number; winners?: number[] }) => {
    page.bye = b;
    if (b.scoreboard.length > 0 && !page.game) hud.players(page.playerId, b.scoreboard);
    // A team game's result is its team's (a winner or a draw), else the winners' names.
    const nameOf = (id: number) => b.scoreboard.find((l) => l.playerId === id)?.name || `#${id}`;
    const winners = b.winners && b.winners.length > 0 ? b.winners : b.winner ? [b.winner] : [];
    const result = resultText(page.game, b.winningTeam ?? 0, winners, nameOf);
    hud.setStatus(b.matchOver ? `match over${result ? ': ' + result : ''}` : `disconnected: ${b.reason}`);
  });

  const draw = (now: number) => {
    if (controls) {
      const c = controls.read();
      client.input(c.thrust, c.turn, c.buttons);
    }
    const state = client.stateAt(now);
    const bodies = (state.bodies as Body[]).filter((b) => !staticIds.has(b.id));
    // The own ship, predicted (after a respawn too: the SDK follows the new body); before the
    // first snapshot placed it, the player's ship as the server last sent it. A spectator's view
    // is the whole world, centred on its middle (positions are in [0, size)).
    const mine = spectating ? null : state.own ?? bodies.find((b) => b.owner === page.playerId && b.kind === KIND_SHIP);
    if (mine) centre = { x: mine.x, y: mine.y };
    else if (spectating) centre = { x: world.width / 2, y: world.height / 2 };
    const span = spectating && world.width > 0 ? Math.max(world.width, world.height) : VIEW_METRES;
    for (const b of bodies) lastSeen.set(b.id, { x: b.x, y: b.y, r: boundingRadius(b) });
    if (lastSeen.size > 4 * bodies.length + 64) {
      const live = new Set(bodies.map((b) => b.id));
      for (const id of lastSeen.keys()) if (!live.has(id)) lastSeen.delete(id);
    }
    if (!spectating) {
      // The own bullets against the others as drawn: what this player sees hit (src/claims.ts).
      const bullet = bulletKind();
      const drawnBullet = bodies.find((b) => b.kind === bullet && b.shape);
      if (drawnBullet) bulletRadius = boundingRadius(drawnBullet);
      const targets = bodies.filter((b) => !b.predicted && b.kind !== bullet && b.owner !== page.playerId && b.id !== 0);
      flashes.push(...claims.frame(world, client.session.ownBullets(), bulletRadius, targets, now));
      page.hitsClaimed = claims.claimed;
    }
    // The own shots the server has not shown yet: each bullet appears as it is fired.
    for (const s of state.shots) bodies.push({ id: 0, owner: page.playerId, x: s.x, y: s.y, angle: 0, kind: KIND_BULLET, predicted: true });
    page.predictedShotsDrawn += state.shots.length;
    flashes = flashes.filter((f) => now - f.born < f.life);
    hits = hits.filter((m) => now - m.born < m.life);
    if (page.debugLag && state.view) {
      const bullet = bulletKind();
      const targets = bodies
        .filter((b) => !b.predicted && b.owner !== page.playerId && b.kind !== bullet && b.id !== 0)
        .map((b) => ({ x: b.x, y: b.y, radius: boundingRadius(b) }));
      views.push({ moment: state.view.tick * 256 + state.view.fraction, targets });
      if (views.length > LAG_VIEWS) views.shift();
      lagShots = lagShots.filter((s) => now - s.born < s.life);
    }
    page.lagShapes = painter.frame(world, page.playerId, centre, statics, bodies, flashes, now, span, hits, lagShots);
    page.lagShapesDrawn += page.lagShapes;
    page.drawn = bodies.length;
    page.gamePageFrames = painter.gamePageFrames;
    if (unrendered !== null) keep(page.arrivalToRender, performance.now() - unrendered);
    unrendered = null;

    ++page.frames;
    frameTimes.push(now);
    frameTimes = frameTimes.filter((t) => now - t < 1000);
    snapshotTimes = snapshotTimes.filter((t) => now - t < 1000);
    page.fps = frameTimes.length;
    page.snapshotRate = snapshotTimes.length;
    if (page.frames % 10 === 0) hud.figures(client.rtt, page.snapshotRate, page.predictionError, client.inputsLeftOut);
    if (!page.bye) requestAnimationFrame(draw);
  };
  requestAnimationFrame(draw);
}

main().catch((e: unknown) => {
  const message = e instanceof Error ? e.message : String(e);
  if (window.arenaPage) window.arenaPage.error = message;
  const status = document.getElementById('status');
  if (status) {
    status.textContent = `cannot start: ${message}`;
    status.hidden = false;
  }
});
