// The HUD: the match and its mode with an invite link, the player's score and lives (or, for
// a spectator, that it is spectating), the scoreboard, and the connection's figures (ping, snapshots a second, the prediction error). Written into the page's elements at most a few
// times a second; the numbers are also data-* attributes so that tests read them exactly.

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

export class Hud {
  private readonly score = el('score');
  private readonly lives = el('lives');
  private readonly board = el('scoreboard');
  private readonly ping = el('ping');
  private readonly rate = el('rate');
  private readonly error = el('prediction-error');
  private readonly leftOut = el('left-out');
  private readonly status = el('status');

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
    const own = ['score', 'kills', 'deaths', 'shots', 'hits', 'lives'];
    this.game = game && game.playerFields.some((f) => !own.includes(f.name)) ? game : null;
    this.tickRate = tickRate;
    if (!this.game) return;
    const head = document.createElement('tr');
    for (const label of ['player', ...this.game.playerFields.map((f) => f.label)]) {
      const th = document.createElement('th');
      th.textContent = label;
      head.appendChild(th);
    }
    (el('scoreboard-table') as HTMLTableElement).tHead?.replaceChildren(head);
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
    const value = (id: number, k: number) => (k < 0 ? 0 : values.get(id)?.[k] ?? 0);
    const me = lines.find((l) => l.playerId === own);
    this.score.textContent = String(value(own, rank));
    this.score.dataset.value = String(value(own, rank));
    this.lives.textContent = '–';
    const order = game.rankAscending ? 1 : -1;
    const sorted = [...lines].sort((a, b) => order * (value(a.playerId, rank) - value(b.playerId, rank)) || a.playerId - b.playerId);
    const shownLines = sorted.slice(0, 10);
    if (me && !shownLines.includes(me)) shownLines.push(me);
    const team = teamField(game);
    this.board.replaceChildren(
      ...shownLines.map((l) => {
        const tr = document.createElement('tr');
        if (l.playerId === own) tr.className = 'me';
        const colour = team >= 0 ? teamColour(game, value(l.playerId, team)) : null;
        if (colour) tr.style.color = colour;
        const cells = [l.name || `#${l.playerId}`, ...game.playerFields.map((f, k) => shown(game, f, value(l.playerId, k), this.tickRate))];
        for (const text of cells) {
          const td = document.createElement('td');
          td.textContent = text;
          tr.appendChild(td);
        }
        return tr;
      }),
    );
    // The teams' own values: "red 1 · blue 0".
    const line = el('teams');
    line.hidden = teams.size === 0;
    line.replaceChildren(
      ...[...teams].map(([number, held], i) => {
        const span = document.createElement('span');
        span.dataset.team = teamName(game, number);
        span.dataset.value = String(held[0] ?? 0);
        span.style.color = teamColour(game, number) ?? '';
        span.textContent = `${i > 0 ? ' · ' : ''}${teamName(game, number)} ${game.teamFields.map((_, k) => held[k] ?? 0).join(' ')}`;
        return span;
      }),
    );
  }

  players(own: number, lines: Line[]): void {
    const me = lines.find((l) => l.playerId === own);
    // (A spectator's line is gone from the page; writing into the detached elements is harmless.)
    this.score.textContent = String(me?.score ?? 0);
    this.score.dataset.value = String(me?.score ?? 0);
    this.lives.textContent = me ? (me.state === 2 ? 'out' : String(me.lives)) : '–';
    const sorted = [...lines].sort((a, b) => b.score - a.score || a.playerId - b.playerId);
    // The top ten, and the own line below them when it is not among them.
    const shown = sorted.slice(0, 10);
    if (me && !shown.includes(me)) shown.push(me);
    const rows = shown.map((l) => {
      const tr = document.createElement('tr');
      if (l.playerId === own) tr.className = 'me';
      for (const text of [l.name || `#${l.playerId}`, String(l.score), `${l.kills}/${l.deaths}`, STATE[l.state] ?? '']) {
        const td = document.createElement('td');
        td.textContent = text;
        tr.appendChild(td);
      }
      return tr;
    });
    this.board.replaceChildren(...rows);
  }

  figures(pingMs: number | null, snapshotsPerSecond: number, predictionErrorM: number | null, inputsLeftOut: number): void {
    this.ping.textContent = pingMs === null ? '–' : `${pingMs.toFixed(1)} ms`;
    this.rate.textContent = `${snapshotsPerSecond.toFixed(0)}/s`;
    this.error.textContent = predictionErrorM === null ? '–' : `${(predictionErrorM * 100).toFixed(1)} cm`;
    this.leftOut.textContent = String(inputsLeftOut);
  }
}
