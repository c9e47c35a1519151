// What the page knows of the game it plays: the manifest the server sent in the Welcome
// (protocol/README.md, "Game manifest"). With it the page draws any game: the scoreboard's
// columns and order, team colours, body styles by tag, event messages and the keys. Without one
// (a server that sends none) the page plays as it always did.

import type { GameField, GameManifest } from './arena-sdk.mjs';

export type Field = GameField;
export type Manifest = GameManifest;

export const FIELD_TEAM = 1;

/** Team `team`'s name (1 is the first), '–' for none. */
export function teamName(game: Manifest, team: number): string {
  return game.teams[team - 1]?.name ?? (team === 0 ? '–' : `team ${team}`);
}

export function teamColour(game: Manifest, team: number): string | null {
  return game.teams[team - 1]?.colour ?? null;
}

/** The index of the player field holding each player's team, or -1. */
export function teamField(game: Manifest): number {
  return game.playerFields.findIndex((f) => f.kind === FIELD_TEAM);
}

/** A declared value as a scoreboard cell shows it. */
export function shown(game: Manifest, field: Field, value: number, tickRate: number): string {
  if (field.kind === FIELD_TEAM) return teamName(game, value);
  if (field.kind === 2 && tickRate > 0) return `${(value / tickRate).toFixed(1)} s`;
  return String(value);
}

/** An event's message with its values in place: a player by name, a team by its name. */
export function eventText(game: Manifest, kind: number, values: number[], nameOf: (player: number) => string): string {
  const spec = game.events[kind];
  if (!spec) return `event ${kind}`;
  return spec.message.replace(/\{([a-z0-9_]+)\}/g, (whole, key: string) => {
    const at = spec.values.indexOf(key);
    if (at < 0) return whole;
    const v = values[at] ?? 0;
    if (key === 'player' || key.endsWith('_player')) return nameOf(v);
    if (key === 'team' || key.endsWith('_team')) return v === 0 ? 'a draw' : teamName(game, v);
    return String(v);
  });
}

/** A match's result as the rules give it, in a few words: a team game's winning team ("red
 *  win") or "a draw"; otherwise the winning player ("NAME wins"), the players tied at the top
 *  ("A and B tie"), or '' for nobody. */
export function resultText(game: Manifest | null, winningTeam: number, winners: number[], nameOf: (player: number) => string): string {
  if (game && game.teams.length > 0) return winningTeam ? `${teamName(game, winningTeam)} win` : 'a draw';
  if (winners.length === 0) return '';
  const names = winners.map(nameOf);
  return names.length === 1 ? `${names[0]} wins` : `${names.slice(0, -1).join(', ')} and ${names[names.length - 1]} tie`;
}
