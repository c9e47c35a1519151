// What the SDK reads from a frame with the TypeScript that flatc generates from
// protocol/arena.fbs. Only frames the WebAssembly core verified first come here: the npm
// FlatBuffers runtime has no verifier.
import * as flatbuffers from 'flatbuffers';
import { Bye, GameEvent as FbGameEvent, GameEventRecord as FbGameEventRecord, GameValue as FbGameValue, Message, PlayerLine as FbPlayerLine, Pong, Reject, RejectCode, Snapshot, Welcome } from '@arena/protocol';
// Welcome.game's root: a nested buffer, so the generated index leaves it out.
import { GameManifest as FbGameManifest } from '@arena/protocol/game-manifest';

export interface PlayerLine {
  playerId: number;
  score: number;
  kills: number;
  deaths: number;
  shots: number;
  hits: number;
  lives: number;
  /** playing 0, respawning 1, out 2 (protocol PlayerState). */
  state: number;
}

export interface GameEvent {
  sequence: number;
  tick: number;
  /** rock_hit 0, ship_destroyed 1, respawn 2, wave 3, shot_rewound 4 (protocol GameEventKind). */
  kind: number;
  size: number;
  player: number;
  other: number;
  body: number;
  value: number;
}

/** What a game declares of itself (protocol/README.md, "Game manifest"). */
export interface GameField {
  /** Its key: [a-z0-9_]. */
  name: string;
  label: string;
  /** count 0, team 1, ticks 2 (protocol GameFieldKind). */
  kind: number;
}

export interface GameManifest {
  name: string;
  playerFields: GameField[];
  teamFields: GameField[];
  /** Team k is teams[k - 1]. */
  teams: { name: string; colour: string }[];
  /** The player field that orders the scoreboard; '' none. */
  rankField: string;
  rankAscending: boolean;
  /** GameRecord.kind k is events[k]; values name what GameRecord.values hold. */
  events: { name: string; values: string[]; message: string }[];
  bodyTags: { kind: number; name: string; style: string; colour: string }[];
  inputs: { name: string; button: number; key: string }[];
}

/** One declared value: owner is a player id (playerValues) or a team number (teamValues). */
export interface GameValue {
  owner: number;
  field: number;
  value: number;
}

/** One of the game's declared events. */
export interface GameRecord {
  sequence: number;
  tick: number;
  kind: number;
  values: number[];
}

export interface WelcomeFields {
  playerId: number;
  entityId: number;
  tick: number;
  tickRate: number;
  snapshotRate: number;
  preset: string;
  worldConfig: string;
  viewRadius: number;
  /** The id of the match joined ('default' for the server's default match). */
  match: string;
  /** The mode it plays. */
  mode: string;
  /** What the game declares of itself; null when it declares nothing (the sandbox). */
  game: GameManifest | null;
}

export interface SnapshotExtras {
  players: PlayerLine[];
  names: Map<number, string>;
  events: GameEvent[];
  playerValues: GameValue[];
  teamValues: GameValue[];
  records: GameRecord[];
}

export interface ByeFields {
  reason: string;
  /** RejectCode name when the server refused or dropped the client. */
  code?: string;
  matchOver: boolean;
  winner: number;
  scoreboard: (PlayerLine & { name: string })[];
  /** The final declared values, the winning team (0: none) and the winning players. */
  playerValues?: GameValue[];
  teamValues?: GameValue[];
  winningTeam?: number;
  winners?: number[];
}

export function readMessage(frame: Uint8Array): Message {
  return Message.getSizePrefixedRootAsMessage(new flatbuffers.ByteBuffer(frame));
}

function line(p: FbPlayerLine): PlayerLine {
  return { playerId: p.playerId(), score: p.score(), kills: p.kills(), deaths: p.deaths(), shots: p.shots(), hits: p.hits(), lives: p.lives(), state: p.state() };
}

function text(s: string | null): string {
  return s ?? '';
}

/** A GameManifest buffer (protocol/manifest.hpp's encode_manifest) as plain data; null for no
 *  bytes (a game that declares nothing). Only bytes the WebAssembly core verified or made come
 *  here: the Welcome's (Welcome.game, a buffer of its own in arena.fbs) and a replayed game's
 *  (ReplayPlayer.manifest). */
export function decodeManifest(bytes: Uint8Array | null): GameManifest | null {
  if (bytes === null || bytes.length === 0) return null;
  const g = FbGameManifest.getRootAsGameManifest(new flatbuffers.ByteBuffer(bytes));
  const fields = (count: number, at: (i: number) => { name(): string | null; label(): string | null; kind(): number } | null): GameField[] => {
    const out: GameField[] = [];
    for (let i = 0; i < count; ++i) {
      const f = at(i);
      if (f) out.push({ name: text(f.name()), label: text(f.label()), kind: f.kind() });
    }
    return out;
  };
  const manifest: GameManifest = {
    name: text(g.name()),
    playerFields: fields(g.playerFieldsLength(), (i) => g.playerFields(i)),
    teamFields: fields(g.teamFieldsLength(), (i) => g.teamFields(i)),
    teams: [],
    rankField: text(g.rankField()),
    rankAscending: g.rankAscending(),
    events: [],
    bodyTags: [],
    inputs: [],
  };
  for (let i = 0; i < g.teamsLength(); ++i) {
    const t = g.teams(i);
    if (t) manifest.teams.push({ name: text(t.name()), colour: text(t.colour()) });
  }
  for (let i = 0; i < g.eventsLength(); ++i) {
    const e = g.events(i);
    if (!e) continue;
    const values: string[] = [];
    for (let k = 0; k < e.valuesLength(); ++k) values.push(e.values(k));
    manifest.events.push({ name: text(e.name()), values, message: text(e.message()) });
  }
  for (let i = 0; i < g.bodyTagsLength(); ++i) {
    const b = g.bodyTags(i);
    if (b) manifest.bodyTags.push({ kind: b.kind(), name: text(b.name()), style: text(b.style()), colour: text(b.colour()) });
  }
  for (let i = 0; i < g.inputsLength(); ++i) {
    const k = g.inputs(i);
    if (k) manifest.inputs.push({ name: text(k.name()), button: k.button(), key: text(k.key()) });
  }
  return manifest;
}

function values(count: number, at: (i: number) => FbGameValue | null): GameValue[] {
  const out: GameValue[] = [];
  for (let i = 0; i < count; ++i) {
    const v = at(i);
    if (v) out.push({ owner: v.owner(), field: v.field(), value: v.value() });
  }
  return out;
}

export function readWelcome(m: Message): WelcomeFields {
  const w: Welcome = m.payload(new Welcome());
  return {
    playerId: w.playerId(),
    entityId: w.entityId(),
    tick: w.tick(),
    tickRate: w.tickRate(),
    snapshotRate: w.snapshotRate(),
    preset: (w.preset() as string | null) ?? '',
    worldConfig: (w.worldConfig() as string | null) ?? '',
    viewRadius: w.viewRadius(),
    match: (w.match() as string | null) ?? '',
    mode: (w.mode() as string | null) ?? '',
    game: decodeManifest(w.gameArray()),
  };
}

export function readSnapshotExtras(m: Message): SnapshotExtras {
  const s: Snapshot = m.payload(new Snapshot());
  const players: PlayerLine[] = [];
  for (let i = 0; i < s.playersLength(); ++i) players.push(line(s.players(i) as FbPlayerLine));
  const names = new Map<number, string>();
  const count = Math.min(s.playerNameIdsLength(), s.playerNamesLength());
  for (let i = 0; i < count; ++i) names.set(s.playerNameIds(i) as number, (s.playerNames(i) as string | null) ?? '');
  const events: GameEvent[] = [];
  for (let i = 0; i < s.eventsLength(); ++i) {
    const e = s.events(i) as FbGameEvent;
    events.push({ sequence: e.sequence(), tick: e.tick(), kind: e.kind(), size: e.size(), player: e.player(), other: e.other(), body: e.body(), value: e.value() });
  }
  const records: GameRecord[] = [];
  for (let i = 0; i < s.gameEventsLength(); ++i) {
    const r = s.gameEvents(i) as FbGameEventRecord;
    records.push({ sequence: r.sequence(), tick: r.tick(), kind: r.kind(), values: [r.v0(), r.v1(), r.v2(), r.v3()] });
  }
  return {
    players,
    names,
    events,
    playerValues: values(s.playerValuesLength(), (i) => s.playerValues(i)),
    teamValues: values(s.teamValuesLength(), (i) => s.teamValues(i)),
    records,
  };
}

export function readBye(m: Message): ByeFields {
  const b: Bye = m.payload(new Bye());
  const scoreboard: (PlayerLine & { name: string })[] = [];
  for (let i = 0; i < b.scoreboardLength(); ++i) {
    const name = i < b.scoreboardNamesLength() ? ((b.scoreboardNames(i) as string | null) ?? '') : '';
    scoreboard.push({ ...line(b.scoreboard(i) as FbPlayerLine), name });
  }
  const winners: number[] = [];
  for (let i = 0; i < b.winnersLength(); ++i) winners.push(b.winners(i) as number);
  return {
    reason: (b.reason() as string | null) ?? '',
    matchOver: b.matchOver(),
    winner: b.winner(),
    scoreboard,
    playerValues: values(b.playerValuesLength(), (i) => b.playerValues(i)),
    teamValues: values(b.teamValuesLength(), (i) => b.teamValues(i)),
    winningTeam: b.winningTeam(),
    winners,
  };
}

export function readReject(m: Message): ByeFields {
  const r: Reject = m.payload(new Reject());
  return { reason: (r.reason() as string | null) ?? '', code: RejectCode[r.code()] ?? String(r.code()), matchOver: false, winner: 0, scoreboard: [] };
}

export function readPong(m: Message): { clientTime: number; serverTick: number } {
  const p: Pong = m.payload(new Pong());
  return { clientTime: Number(p.clientTime()), serverTick: p.serverTick() };
}
