// The HUD: the match and its mode with an invite link, the player's score and lives (or, for
// a spectator, that it is spectating), the scoreboard, and the connection's figures (ping, snapshots a second, the prediction error). Written into the page's elements at most a few
// times a second; the numbers are also data-* attributes so that tests read them exactly.
// The scoreboard's head, rows and team line are functions of plain data (boardHead, boardRows,
// teamSpans), so that the replay page draws a replayed match's scoreboard with them too.

import { Manifest, shown, teamColour, teamField, teamName } from './game.js';

export interface Line {
  playerId: number;
  name: string;
  score: number;
  kills: number;
  deaths: number;
  lives: number;
  state: number; // playing 0, respawning 1, out 2
}

const STATE = ['', 'respawning', 'out'];

/** The help line from the game's declared keys: "arrows turn and run · Space kick · ShiftLeft dash". */
function help(game: Manifest): void {
  el('help').textContent = ['arrows turn and move', ...game.inputs.map((i) => `${i.key} ${i.name}`)].join(' · ');
}

function el(id: string): HTMLElement {
  const e = document.getElementById(id);
  if (!e) throw new Error(`the page has no #${id}`);
  return e;
}

/** The manifest whose fields make the scoreboard's columns, or null: the protocol's own columns
 *  (score, k/d, state) already show every field it declares (Asteroids), or there is none. */
export function boardGame(game: Manifest | null): Manifest | null {
  const own = ['score', 'kills', 'deaths', 'shots', 'hits', 'lives'];
  return game && game.playerFields.some((f) => !own.includes(f.name)) ? game : null;
}

function row(cells: string[], tag: 'td' | 'th'): HTMLTableRowElement {
  const tr = document.createElement('tr');
  for (const text of cells) {
    const cell = document.createElement(tag);
    cell.textContent = text;
    tr.appendChild(cell);
  }
  return tr;
}

/** The scoreboard's column titles: the player, then the game's fields (boardGame), or the
 *  protocol's own columns. */
export function boardHead(game: Manifest | null): HTMLTableRowElement {
  return row(game ? ['player', ...game.playerFields.map((f) => f.label)] : ['player', 'score', 'k/d', ''], 'th');
}

/** The scoreboard's rows: the top ten by the game's rank field (by score without a game), and
 *  `own`'s line below them when it is not among them (`own` 0: nobody's). `game` is boardGame's;
 *  `values` holds each player's declared values by id, in the manifest's field order. A line
 *  without a name shows `#id`. */
export function boardRows(game: Manifest | null, own: number, lines: Line[], values: Map<number, number[]>, tickRate: number): HTMLTableRowElement[] {
  const me = lines.find((l) => l.playerId === own);
  const rank = game ? game.playerFields.findIndex((f) => f.name === game.rankField) : -1;
  const value = (id: number, k: number) => (k < 0 ? 0 : values.get(id)?.[k] ?? 0);
  const sorted = game
    ? [...lines].sort((a, b) => (game.rankAscending ? 1 : -1) * (value(a.playerId, rank) - value(b.playerId, rank)) || a.playerId - b.playerId)
    : [...lines].sort((a, b) => b.score - a.score || a.playerId - b.playerId);
  const shownLines = sorted.slice(0, 10);
  if (me && !shownLines.includes(me)) shownLines.push(me);
  const team = game ? teamField(game) : -1;
  return shownLines.map((l) => {
    const name = l.name || `#${l.playerId}`;
    const cells = game
      ? [name, ...game.playerFields.map((f, k) => shown(game, f, value(l.playerId, k), tickRate))]
      : [name, String(l.score), `${l.kills}/${l.deaths}`, STATE[l.state] ?? ''];
    const tr = row(cells, 'td');
    if (l.playerId === own) tr.className = 'me';
    const colour = game && team >= 0 ? teamColour(game, value(l.playerId, team)) : null;
    if (colour) tr.style.color = colour;
    return tr;
  });
}

/** The teams' own values, by team number: "red 1 · blue 0", each team in its colour, with its
 *  name and first value as data-team and data-value. */
export function teamSpans(game: Manifest, teams: Map<number, number[]>): HTMLSpanElement[] {
  return [...teams].map(([number, held], i) => {
    const span = document.createElement('span');
    span.dataset.team = teamName(game, number);
    span.dataset.value = String(held[0] ?? 0);
    span.style.color = teamColour(game, number) ?? '';
    span.textContent = `${i > 0 ? ' · ' : ''}${teamName(game, number)} ${game.teamFields.map((_, k) => held[k] ?? 0).join(' ')}`;
    return span;
  });
}

export class Hud {
  private readonly score = el('score');
  private readonly lives = el('lives');
  private readonly board = el('scoreboard');
  private readonly ping = el('ping');
  private readonly rate = el('rate');
  private readonly error = el('prediction-error');
  private readonly leftOut = el('left-out');
  private readonly status = el('status');
  private readonly hits = el('hits');

  private hitStreak = 0;
  private hitTimer: ReturnType<typeof setTimeout> | null = null;

  private shown = 0;
  private game: Manifest | null = null;
  private tickRate = 0;

  /** A spectator has no score and no lives: the line says that it watches. */
  spectating(): void {
    const own = el('own');
    own.textContent = 'spectating';
    own.dataset.spectating = 'true';
    el('help').textContent = 'spectating: the whole match, no ship of your own';
  }

  /** Which match this is (Welcome.match, Welcome.mode), and the link that brings a friend into it. */
  match(id: string, mode: string, invite: string): void {
    el('match-id').textContent = id;
    el('match-mode').textContent = mode || '–';
    const link = el('invite') as HTMLAnchorElement;
    link.href = invite;
    link.title = `${invite}: send it to a friend, it joins this match`;
    el('invite-item').hidden = false;
  }

  /** The way back to the lobby, shown from the start: a refused join needs it most. */
  lobby(href: string): void {
    (el('to-lobby') as HTMLAnchorElement).href = href;
  }

  setStatus(text: string): void {
    ++this.shown;
    this.status.textContent = text;
    this.status.hidden = text === '';
  }

  /** A message shown for two seconds, unless a lasting one replaces it. */
  flashStatus(text: string): void {
    this.setStatus(text);
    const shown = ++this.shown;
    setTimeout(() => {
      if (this.shown === shown && this.status.textContent === text) this.setStatus('');
    }, 2000);
  }

  /** The game's manifest: its scoreboard's columns, its teams. Its fields replace the protocol's
   *  own columns unless those already show them all (Asteroids). */
  declare(game: Manifest | null, tickRate: number): void {
    this.game = boardGame(game);
    this.tickRate = tickRate;
    if (!this.game) return;
    (el('scoreboard-table') as HTMLTableElement).tHead?.replaceChildren(boardHead(this.game));
    const rank = this.game.playerFields.find((f) => f.name === this.game?.rankField);
    el('own').firstElementChild?.replaceChildren(document.createTextNode(`${(rank?.label ?? 'score').toLowerCase()} `), this.score);
    help(this.game);
  }

  /** The game's declared scoreboard (declare() first): `values` by player id in the manifest's
   *  field order, `teams` by team number. */
  declared(own: number, lines: Line[], values: Map<number, number[]>, teams: Map<number, number[]>): void {
    const game = this.game;
    if (!game) return this.players(own, lines);
    const rank = game.playerFields.findIndex((f) => f.name === game.rankField);
    const mine = rank < 0 ? 0 : values.get(own)?.[rank] ?? 0;
    this.score.textContent = String(mine);
    this.score.dataset.value = String(mine);
    this.lives.textContent = '–';
    this.board.replaceChildren(...boardRows(game, own, lines, values, this.tickRate));
    const line = el('teams');
    line.hidden = teams.size === 0;
    line.replaceChildren(...teamSpans(game, teams));
  }

  players(own: number, lines: Line[]): void {
    const me = lines.find((l) => l.playerId === own);
    // (A spectator's line is gone from the page; writing into the detached elements is harmless.)
    this.score.textContent = String(me?.score ?? 0);
    this.score.dataset.value = String(me?.score ?? 0);
    this.lives.textContent = me ? (me.state === 2 ? 'out' : String(me.lives)) : '–';
    this.board.replaceChildren(...boardRows(null, own, lines, new Map(), this.tickRate));
  }

  /** A hit of this player's the server confirmed: "hit" (×n for a run of them) shown for
   *  1.2 s from the last one; data-total holds every confirmed hit. */
  hitConfirmed(total: number): void {
    ++this.hitStreak;
    this.hits.textContent = this.hitStreak > 1 ? `hit ×${this.hitStreak}` : 'hit';
    this.hits.dataset.total = String(total);
    this.hits.dataset.streak = String(this.hitStreak);
    this.hits.hidden = false;
    if (this.hitTimer !== null) clearTimeout(this.hitTimer);
    this.hitTimer = setTimeout(() => {
      this.hits.hidden = true;
      this.hitStreak = 0;
      this.hitTimer = null;
    }, 1200);
  }

  figures(pingMs: number | null, snapshotsPerSecond: number, predictionErrorM: number | null, inputsLeftOut: number): void {
    this.ping.textContent = pingMs === null ? '–' : `${pingMs.toFixed(1)} ms`;
    this.rate.textContent = `${snapshotsPerSecond.toFixed(0)}/s`;
    this.error.textContent = predictionErrorM === null ? '–' : `${(predictionErrorM * 100).toFixed(1)} cm`;
    this.leftOut.textContent = String(inputsLeftOut);
  }
}
