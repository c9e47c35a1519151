// The replay page (/replay): plays an arena-server --record file with the server's world in
// WebAssembly (the SDK's ReplayPlayer), drawn as the game page draws a match. The recording
// comes from ?src=URL or from a file the viewer opens. Play, pause, speed 0.25x to 8x and a
// scrub bar (seeking back re-simulates from the start); every recorded hash is compared as
// the world reaches its tick, and the first mismatch stops the replay with both hashes shown.
// Beside the world, the replayed game as the game page shows a live one, from the recording's
// own rules: its scoreboard and teams (hud.ts), its declared events as its manifest words them
// (game.ts) and, once the rules end the match, the result.
// window.arenaReplay holds the figures, for tests and the console.
import { Core, ReplayPlayer } from './arena-sdk.mjs';
import type { GameManifest, ReplayLine } from './arena-sdk.mjs';
import { Body, Painter } from './draw.js';
import { eventText, resultText, teamColour } from './game.js';
import { findGamePage, readWorldConfig } from './game_page.js';
import { gamePages } from '@arena/game-pages';
import { boardGame, boardHead, boardRows, teamSpans } from './hud.js';

// Events shown in the log, newest first (the SDK keeps the newest 64).
const EVENTS_SHOWN = 10;

interface ReplayState {
  /** Where the recording came from: the ?src URL or the file's name. */
  source: string;
  loaded: boolean;
  playing: boolean;
  speed: number;
  tick: number;
  startTick: number;
  endTick: number;
  /** Computed at `tick`, and the recording's own for it ('' when it holds none there). */
  hash: string;
  recordedHash: string;
  hashesChecked: number;
  hashesTotal: number;
  /** The first mismatch or the file's problem; '' while every hash matched. */
  error: string;
  cutShort: string;
  frames: number;
  /** The replayed game (its manifest's name; '' for none, the sandbox), its scoreboard at
   *  `tick` (the SDK's lines), its events up to `tick` as the log tells them (oldest first), and
   *  the result once its rules ended the match ('' before). */
  game: string;
  /** The game's page module drawing the replay ('' for none: web/page/src/game_page.ts). */
  gamePage: string;
  players: ReplayLine[];
  events: { sequence: number; tick: number; kind: number; name: string; values: number[]; text: string }[];
  result: string;
}

declare global {
  interface Window {
    arenaReplay: ReplayState;
  }
}

function el<T extends HTMLElement>(id: string): T {
  const e = document.getElementById(id);
  if (!e) throw new Error(`the page has no #${id}`);
  return e as T;
}

// m:ss into the recording.
function clock(ticks: number, tickRate: number): string {
  const seconds = Math.floor(ticks / Math.max(tickRate, 1));
  return `${Math.floor(seconds / 60)}:${String(seconds % 60).padStart(2, '0')}`;
}

/** The replayed game beside the canvas: the scoreboard, the teams, the event log and the result,
 *  drawn with the game page's own helpers (hud.ts, game.ts). */
class GamePanel {
  private readonly panel = el('hud');
  private readonly head = el<HTMLTableSectionElement>('scoreboard-head');
  private readonly board = el('scoreboard');
  private readonly teams = el('teams');
  private readonly log = el<HTMLOListElement>('events');
  private readonly result = el('result');
  private game: GameManifest | null = null;
  private tickRate = 0;
  private startTick = 0;
  private teamOf = new Map<number, number>(); // player id -> team, as last drawn

  /** A new recording: its manifest and rates. */
  open(game: GameManifest | null, tickRate: number, startTick: number): void {
    this.game = game;
    this.tickRate = tickRate;
    this.startTick = startTick;
    this.head.replaceChildren(boardHead(boardGame(game)));
    this.teamOf.clear();
  }

  /** No recording (closed, or one that would not open): no panel. */
  clear(): void {
    this.panel.hidden = true;
    this.game = null;
    this.teamOf.clear();
  }

  /** A body's owner's team colour, from the scoreboard last drawn. */
  ownerColour = (owner: number): string | null => (this.game ? teamColour(this.game, this.teamOf.get(owner) ?? 0) : null);

  /** The game at the player's tick, into the page and `state`. */
  draw(player: ReplayPlayer, state: ReplayState): void {
    // A player as the recording names it (one who has left too: events name them), else "player N".
    const nameOf = (id: number): string => player.nameOf(id) || `player ${id}`;
    const lines = player.scoreboard();
    for (const l of lines) this.teamOf.set(l.playerId, l.team);
    const named = lines.map((l) => ({ ...l, name: l.name || `player ${l.playerId}` }));
    const values = new Map(lines.map((l) => [l.playerId, l.values]));
    const game = this.game;
    // A sandbox recording keeps no score: no panel at all.
    this.panel.hidden = lines.length === 0 && !game;
    this.board.replaceChildren(...boardRows(boardGame(game), 0, named, values, this.tickRate));
    const teams = new Map(player.teams().map((t) => [t.team, t.values]));
    this.teams.hidden = !game || teams.size === 0;
    this.teams.replaceChildren(...(game ? teamSpans(game, teams) : []));

    const events = game ? player.events().map((e) => ({ ...e, name: game.events[e.kind]?.name ?? '', text: eventText(game, e.kind, e.values, nameOf) })) : [];
    this.log.replaceChildren(
      ...events
        .slice(-EVENTS_SHOWN)
        .reverse()
        .map((e) => {
          const li = document.createElement('li');
          li.dataset.tick = String(e.tick);
          li.dataset.kind = e.name;
          li.textContent = `${clock(e.tick - this.startTick, this.tickRate)} ${e.text}`;
          return li;
        }),
    );
    this.log.hidden = events.length === 0;

    const r = player.result();
    const result = r.finished ? `match over: ${resultText(game, r.winningTeam, r.winners, nameOf) || 'no winner'}` : '';
    this.result.textContent = result;
    this.result.hidden = result === '';
    state.game = game?.name ?? '';
    state.players = named;
    state.events = events;
    state.result = result;
  }
}

// "tick T: hash mismatch: expected E, actual A" (web/sdk/core/c_api.cpp) as a sentence.
function describeFailure(error: string): string {
  const m = /^tick (\d+): hash mismatch: expected ([0-9a-f]+), actual ([0-9a-f]+)$/.exec(error);
  if (!m) return `replay failed: ${error}`;
  return `hash MISMATCH at tick ${m[1]}: the recording has ${m[2]}, this replay computed ${m[3]}`;
}

async function main(): Promise<void> {
  const painter = new Painter(el<HTMLCanvasElement>('game'));
  const playButton = el<HTMLButtonElement>('play');
  const speedSelect = el<HTMLSelectElement>('speed');
  const scrub = el<HTMLInputElement>('scrub');
  const tickText = el('tick');
  const hashesText = el('hashes');
  const sourceText = el('source');
  const status = el('status');
  const state: ReplayState = {
    source: '', loaded: false, playing: false, speed: Number(speedSelect.value), tick: 0, startTick: 0, endTick: 0, hash: '', recordedHash: '',
    hashesChecked: 0, hashesTotal: 0, error: '', cutShort: '', frames: 0, game: '', gamePage: '', players: [], events: [], result: '',
  };
  const panel = new GamePanel();
  window.arenaReplay = state;
  const setStatus = (text: string) => {
    status.textContent = text;
    status.hidden = text === '';
  };

  const core = await Core.load();
  let player: ReplayPlayer | null = null;
  let carry = 0; // ticks owed to the clock, below one
  let last = 0;
  let panelTick = -1; // the tick the game panel shows

  const show = () => {
    if (!player) return;
    state.tick = player.tick;
    state.hash = player.hash;
    state.recordedHash = player.recordedHash;
    state.hashesChecked = player.hashesChecked;
    state.hashesTotal = player.hashesTotal;
    state.error = player.error;
    tickText.textContent = `tick ${state.tick - state.startTick} / ${state.endTick - state.startTick}`;
    if (document.activeElement !== scrub) scrub.value = String(state.tick);
    playButton.textContent = state.playing ? 'pause' : state.tick >= state.endTick ? 'replay' : 'play';
    if (state.error !== '') {
      hashesText.className = 'failed';
      hashesText.textContent = `hashes verified: ${state.hashesChecked - 1}/${state.hashesTotal} · ${describeFailure(state.error)}`;
    } else {
      hashesText.className = 'verified';
      const at = state.recordedHash !== '' ? ` · tick ${state.tick}: ${state.hash} verified` : '';
      const end = state.tick >= state.endTick ? (state.cutShort !== '' ? ' · recording cut short here' : ' · final hash verified') : '';
      hashesText.textContent = `hashes verified: ${state.hashesChecked}/${state.hashesTotal}${at}${end}`;
    }
    // The scoreboard and the log change with the tick only: not redrawn in a frame that played none.
    if (state.tick !== panelTick) panel.draw(player, state);
    panelTick = state.tick;
    const world = player.world;
    const bodies: Body[] = player.bodies().map((b) => ({ ...b, predicted: false }));
    const span = Math.max(world.width, world.height) || 100;
    painter.frame(world, 0, { x: world.width / 2, y: world.height / 2 }, [], bodies, [], performance.now(), span);
    ++state.frames;
  };

  const pause = () => {
    state.playing = false;
    show();
  };

  const frame = (now: number) => {
    if (player && state.playing) {
      carry += ((now - last) / 1000) * player.tickRate * state.speed;
      const ticks = Math.floor(carry);
      carry -= ticks;
      if (ticks > 0 && !player.step(ticks)) state.playing = false;
      if (player.tick >= state.endTick) state.playing = false;
      show();
    }
    last = now;
    requestAnimationFrame(frame);
  };
  requestAnimationFrame(frame);

  const open = (bytes: Uint8Array, source: string) => {
    player?.close();
    player = null;
    panel.clear();
    state.loaded = false;
    state.playing = false;
    state.source = source;
    sourceText.textContent = source;
    try {
      player = ReplayPlayer.open(core, bytes);
    } catch (e) {
      hashesText.className = 'failed';
      hashesText.textContent = `cannot replay ${source}: ${e instanceof Error ? e.message : String(e)}`;
      state.error = hashesText.textContent;
      return;
    }
    state.startTick = player.startTick;
    state.endTick = player.endTick;
    state.cutShort = player.cutShort;
    const game = player.manifest;
    panel.open(game, player.tickRate, player.startTick);
    painter.setTags(game?.bodyTags ?? null, panel.ownerColour);
    // The game's own drawing, as the game page draws a match (its pitch, its marks).
    const config = readWorldConfig(player.worldConfig);
    const module = findGamePage(gamePages, game, config);
    painter.setGamePage(module?.page ?? null, config, game);
    state.gamePage = module?.name ?? '';
    panelTick = -1;
    scrub.min = String(state.startTick);
    scrub.max = String(state.endTick);
    scrub.disabled = false;
    playButton.disabled = false;
    state.loaded = true;
    setStatus('');
    show();
  };

  playButton.addEventListener('click', () => {
    if (!player) return;
    if (state.playing) return pause();
    if (player.tick >= state.endTick) player.seek(state.startTick);
    carry = 0;
    state.playing = player.error === '';
    show();
  });
  speedSelect.addEventListener('change', () => {
    state.speed = Number(speedSelect.value);
  });
  scrub.addEventListener('input', () => {
    if (!player) return;
    player.seek(Number(scrub.value));
    show();
  });
  el<HTMLInputElement>('file').addEventListener('change', async (e) => {
    const file = (e.target as HTMLInputElement).files?.[0];
    if (file) open(new Uint8Array(await file.arrayBuffer()), file.name);
  });

  const src = new URLSearchParams(location.search).get('src');
  if (src) {
    setStatus(`loading ${src}…`);
    const response = await fetch(src);
    if (!response.ok) throw new Error(`${src}: HTTP ${response.status}`);
    open(new Uint8Array(await response.arrayBuffer()), src);
  } else {
    setStatus('open a recording (an arena-server --record file)');
  }
}

main().catch((e: unknown) => {
  const message = e instanceof Error ? e.message : String(e);
  if (window.arenaReplay) window.arenaReplay.error = message;
  const status = document.getElementById('status');
  if (status) {
    status.textContent = `cannot start: ${message}`;
    status.hidden = false;
  }
});
