// A recording played in the browser with the world in WebAssembly (web/sdk/core/replay_player.hpp):
// step, seek (back means re-simulating from the start), the bodies to draw, the recorded
// hashes checked as it goes, and the replayed game as a live client sees it: its manifest,
// scoreboard, teams, declared events and result.
import { BodyState, Core, Shape } from './core.js';
import { GameManifest, GameRecord, PlayerLine, decodeManifest } from './messages.js';

/** A body of the replayed world with its shape, ready to draw. */
export interface PlayerBody extends BodyState {
  kind: number;
  shape: Shape;
}

/** A line of the replayed scoreboard: the protocol's own columns (PlayerLine), the name, the
 *  team and the game's declared values. */
export interface ReplayLine extends PlayerLine {
  /** The name the player joined with; '' when the recording holds none (recorded before names
   *  were): the viewer chooses what to show instead. */
  name: string;
  /** 0 in a game without teams. */
  team: number;
  /** The game's declared values, in its manifest's playerFields order ([] without a manifest). */
  values: number[];
}

/** A team of the replayed game: its number (1 is the manifest's teams[0]), score and declared
 *  values (in the manifest's teamFields order). */
export interface ReplayTeam {
  team: number;
  score: number;
  values: number[];
}

/** Where the replayed match stands: whether the rules ended it (a clock ran out), the team
 *  winning now (0: none, or a draw) and the players winning now ([]: nobody). */
export interface MatchResult {
  finished: boolean;
  winningTeam: number;
  winners: number[];
}

const SHAPE_BYTES = 76;
// web/sdk/core/c_api.cpp: sdk_line, sdk_team, sdk_event.
const LINE_BYTES = 64;
const TEAM_BYTES = 40;
const EVENT_BYTES = 28;
const MAX_FIELDS = 8;
const EVENT_VALUES = 4;

function int32s(d: DataView, at: number, count: number): number[] {
  const out: number[] = [];
  for (let i = 0; i < count; ++i) out.push(d.getInt32(at + 4 * i, true));
  return out;
}

export class ReplayPlayer {
  private handle: number;

  private constructor(private readonly core: Core, handle: number) {
    this.handle = handle;
  }

  /** Opens a recording (an arena-server --record file) at its start tick. Throws with the
   *  reason when the bytes are not a recording this build can replay, or its start hash is
   *  not the recording's. */
  static open(core: Core, recording: Uint8Array): ReplayPlayer {
    // The player reads the file again when it seeks back: each one its own path.
    const path = `/player-${ReplayPlayer.opened++}.arpl`;
    core.module.FS.writeFile(path, recording);
    const handle = core.withStrings([path], (p) => core.module._arena_player_open(p));
    if (handle === 0) {
      core.module.FS.unlink(path);
      throw new Error(core.text(core.module._arena_replay_open_error()));
    }
    const player = new ReplayPlayer(core, handle);
    player.path = path;
    return player;
  }
  private static opened = 0;
  private path = '';

  /** Frees the module's memory and the file's copy; the player is unusable afterwards. */
  close(): void {
    if (this.handle === 0) return;
    this.core.module._arena_player_free(this.handle);
    this.core.module.FS.unlink(this.path);
    this.handle = 0;
  }

  /** Plays up to `ticks` ticks on (never past the end). False once a hash mismatched or the
   *  file has a problem: `error` says which, and the player stays where it happened. */
  step(ticks: number): boolean {
    return this.core.module._arena_player_step(this.handle, ticks) === 1;
  }
  /** Goes to `tick` (clamped to the recording): on from here, or again from the start. */
  seek(tick: number): boolean {
    return this.core.module._arena_player_seek(this.handle, Math.max(0, Math.floor(tick))) === 1;
  }

  get tick(): number {
    return this.core.module._arena_player_tick(this.handle);
  }
  get startTick(): number {
    return this.core.module._arena_player_start_tick(this.handle);
  }
  get endTick(): number {
    return this.core.module._arena_player_end_tick(this.handle);
  }
  /** The recorded world config, as JSON text (what a Welcome's `worldConfig` holds). */
  get worldConfig(): string {
    return this.core.text(this.core.module._arena_player_world_config(this.handle));
  }
  /** Ticks per second of the recorded server. */
  get tickRate(): number {
    return this.core.module._arena_player_tick_rate(this.handle);
  }
  /** The hash computed at `tick`: 16 hex digits. */
  get hash(): string {
    return this.core.text(this.core.module._arena_player_hash(this.handle));
  }
  /** The recording's hash for `tick`, or '' when it holds none for that tick. */
  get recordedHash(): string {
    return this.core.text(this.core.module._arena_player_recorded_hash(this.handle));
  }
  /** Recorded hashes compared since the start (all matched unless `error` says otherwise). */
  get hashesChecked(): number {
    return this.core.module._arena_player_hashes_checked(this.handle);
  }
  /** Recorded hashes in the file: the start hash, every Hash record and the End. */
  get hashesTotal(): number {
    return this.core.module._arena_player_hashes_total(this.handle);
  }
  /** '' while every hash matched; else "tick T: hash mismatch: expected E, actual A" or the
   *  file's problem. */
  get error(): string {
    return this.core.text(this.core.module._arena_player_error(this.handle));
  }
  /** '' for a complete recording; else why it ends early (no End record: the server was still
   *  recording it, or crashed), after its last complete tick. */
  get cutShort(): string {
    return this.core.text(this.core.module._arena_player_cut_short(this.handle));
  }
  get world(): { wraps: boolean; width: number; height: number } {
    const m = this.core.module;
    return { wraps: m._arena_player_world_wraps(this.handle) === 1, width: m._arena_player_world_width(this.handle), height: m._arena_player_world_height(this.handle) };
  }

  /** What the replayed game declares of itself (its scoreboard's fields, teams, event messages,
   *  body tags), decoded as a live client decodes the Welcome's; null for a game that declares
   *  nothing (the sandbox). */
  get manifest(): GameManifest | null {
    if (this.decoded === undefined) {
      const m = this.core.module;
      this.decoded = decodeManifest(this.core.bytes(m._arena_player_manifest(this.handle), m._arena_player_manifest_size(this.handle)));
    }
    return this.decoded;
  }
  private decoded: GameManifest | null | undefined = undefined;

  /** The scoreboard at `tick`, by player id ([] under rules that keep no score). */
  scoreboard(): ReplayLine[] {
    const m = this.core.module;
    const at = m._arena_player_scoreboard(this.handle);
    const count = m._arena_player_scoreboard_count(this.handle);
    const fields = Math.min(this.manifest?.playerFields.length ?? 0, MAX_FIELDS);
    const d = this.core.view(at, count * LINE_BYTES);
    const out: ReplayLine[] = [];
    for (let i = 0; i < count; ++i) {
      const o = i * LINE_BYTES;
      out.push({
        playerId: d.getUint32(o, true),
        score: d.getUint32(o + 4, true),
        kills: d.getUint32(o + 8, true),
        deaths: d.getUint32(o + 12, true),
        shots: d.getUint32(o + 16, true),
        hits: d.getUint32(o + 20, true),
        lives: d.getUint32(o + 24, true),
        state: d.getUint8(o + 28),
        team: d.getUint8(o + 29),
        values: int32s(d, o + 32, fields),
        name: this.core.text(m._arena_player_scoreboard_name(this.handle, i)),
      });
    }
    return out;
  }

  /** The name player `id` joined with, as far as the replay has come (also of a player who has
   *  left since: events name them); '' when the recording holds none. */
  nameOf(id: number): string {
    return this.core.text(this.core.module._arena_player_name(this.handle, id));
  }

  /** The teams at `tick`, in team order ([] in a game without teams). */
  teams(): ReplayTeam[] {
    const m = this.core.module;
    const at = m._arena_player_teams(this.handle);
    const n = m._arena_player_team_count(this.handle);
    const fields = Math.min(this.manifest?.teamFields.length ?? 0, MAX_FIELDS);
    const d = this.core.view(at, n * TEAM_BYTES);
    const out: ReplayTeam[] = [];
    for (let i = 0; i < n; ++i) {
      const o = i * TEAM_BYTES;
      out.push({ team: d.getUint32(o, true), score: d.getUint32(o + 4, true), values: int32s(d, o + 8, fields) });
    }
    return out;
  }

  /** The game's declared events up to `tick`, oldest first: the newest 64 at most (a seek back
   *  rebuilds them). `sequence` counts them from the recording's start, so a viewer can tell the
   *  new ones; `kind` is the manifest's events[kind], whose `values` name what `values` hold. */
  events(): GameRecord[] {
    const m = this.core.module;
    const at = m._arena_player_events(this.handle);
    const n = m._arena_player_event_count(this.handle);
    const d = this.core.view(at, n * EVENT_BYTES);
    const out: GameRecord[] = [];
    for (let i = 0; i < n; ++i) {
      const o = i * EVENT_BYTES;
      out.push({ sequence: d.getUint32(o, true), tick: d.getUint32(o + 4, true), kind: d.getUint8(o + 8), values: int32s(d, o + 12, EVENT_VALUES) });
    }
    return out;
  }

  /** Where the match stands at `tick`, as the replayed rules say. */
  result(): MatchResult {
    const m = this.core.module;
    const at = m._arena_player_winners(this.handle);
    const n = m._arena_player_winner_count(this.handle);
    const d = this.core.view(at, 4 * n);
    const winners: number[] = [];
    for (let i = 0; i < n; ++i) winners.push(d.getUint32(4 * i, true));
    return { finished: m._arena_player_finished(this.handle) === 1, winningTeam: m._arena_player_winning_team(this.handle), winners };
  }

  /** Every body now, static ones too, by id. */
  bodies(): PlayerBody[] {
    const m = this.core.module;
    const states = this.core.readBodies(m._arena_player_bodies(this.handle), m._arena_player_body_count(this.handle));
    const shapes = this.core.view(m._arena_player_shapes(this.handle), states.length * SHAPE_BYTES);
    return states.map((b, i) => {
      const shape = this.core.readShape(shapes, i * SHAPE_BYTES);
      return { ...b, kind: shape.kind, shape };
    });
  }
}
