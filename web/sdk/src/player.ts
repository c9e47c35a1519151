// A recording played in the browser with the world in WebAssembly (web/sdk/core/replay_player.hpp):
// step, seek (back means re-simulating from the start), the bodies to draw, and the recorded
// hashes checked as it goes.
import { BodyState, Core, Shape } from './core.js';

/** A body of the replayed world with its shape, ready to draw. */
export interface PlayerBody extends BodyState {
  kind: number;
  shape: Shape;
}

const SHAPE_BYTES = 76;

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
