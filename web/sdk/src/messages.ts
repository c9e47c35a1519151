// What the SDK reads from a frame with the TypeScript that flatc generates from
// protocol/arena.fbs. Only frames the WebAssembly core verified first come here: the npm
// FlatBuffers runtime has no verifier.
import * as flatbuffers from 'flatbuffers';
import { Bye, GameEvent as FbGameEvent, Message, PlayerLine as FbPlayerLine, Pong, Reject, RejectCode, Snapshot, Welcome } from '@arena/protocol';

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
  /** rock_hit 0, ship_destroyed 1, respawn 2, wave 3 (protocol GameEventKind). */
  kind: number;
  size: number;
  player: number;
  other: number;
  body: number;
  value: number;
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
}

export interface SnapshotExtras {
  players: PlayerLine[];
  names: Map<number, string>;
  events: GameEvent[];
}

export interface ByeFields {
  reason: string;
  /** RejectCode name when the server refused or dropped the client. */
  code?: string;
  matchOver: boolean;
  winner: number;
  scoreboard: (PlayerLine & { name: string })[];
}

export function readMessage(frame: Uint8Array): Message {
  return Message.getSizePrefixedRootAsMessage(new flatbuffers.ByteBuffer(frame));
}

function line(p: FbPlayerLine): PlayerLine {
  return { playerId: p.playerId(), score: p.score(), kills: p.kills(), deaths: p.deaths(), shots: p.shots(), hits: p.hits(), lives: p.lives(), state: p.state() };
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
  return { players, names, events };
}

export function readBye(m: Message): ByeFields {
  const b: Bye = m.payload(new Bye());
  const scoreboard: (PlayerLine & { name: string })[] = [];
  for (let i = 0; i < b.scoreboardLength(); ++i) {
    const name = i < b.scoreboardNamesLength() ? ((b.scoreboardNames(i) as string | null) ?? '') : '';
    scoreboard.push({ ...line(b.scoreboard(i) as FbPlayerLine), name });
  }
  return { reason: (b.reason() as string | null) ?? '', matchOver: b.matchOver(), winner: b.winner(), scoreboard };
}

export function readReject(m: Message): ByeFields {
  const r: Reject = m.payload(new Reject());
  return { reason: (r.reason() as string | null) ?? '', code: RejectCode[r.code()] ?? String(r.code()), matchOver: false, winner: 0, scoreboard: [] };
}

export function readPong(m: Message): { clientTime: number; serverTick: number } {
  const p: Pong = m.payload(new Pong());
  return { clientTime: Number(p.clientTime()), serverTick: p.serverTick() };
}
