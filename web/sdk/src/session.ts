// One player's session in the WebAssembly core (client_sim/session.hpp, the client core the
// bots run too): no socket, no clock. The client (client.ts) moves its frames; tests drive it directly.
import { BodyState, Core, Shape, StaticBody } from './core.js';

/** The own body as predicted for the last input sent. */
export interface PredictedBody {
  x: number;
  y: number;
  vx: number;
  vy: number;
  angle: number;
  angularVelocity: number;
}

/** One of the player's own bullets where the prediction has it now, as the own ship is drawn
 *  (Asteroids: the shots the core predicts). `bodyId` is its body in the view once the server
 *  confirmed it, 0 while the bullet is predicted only. */
export interface OwnBullet {
  bodyId: number;
  /** The input that fired it. */
  sequence: number;
  x: number;
  y: number;
  vx: number;
  vy: number;
}

export class CoreSession {
  private readonly core: Core;
  private handle: number;

  /** Whether this session watches (Hello.spectator): no body, no inputs. */
  readonly spectator: boolean;

  /** deltaSnapshots: ask the server for delta snapshots (decoded here with its codec).
   *  spectator: join to watch without a body; input() then encodes nothing. */
  constructor(core: Core, deltaSnapshots = true, spectator = false) {
    this.core = core;
    this.spectator = spectator;
    this.handle = core.module._arena_session_new(deltaSnapshots ? 1 : 0, spectator ? 1 : 0);
  }

  /** Frees the session's memory in the module; the object is unusable afterwards. */
  dispose(): void {
    if (this.handle !== 0) this.core.module._arena_session_free(this.handle);
    this.handle = 0;
  }

  /** One frame from the server (one WebSocket message, length prefix included). Returns its
   *  Payload type once verified and handled; 0 when refused (the session ended: error()).
   *  A Reject or Bye is handled and ends the session with its reason. */
  feed(frame: Uint8Array): number {
    const m = this.core.module;
    return m._arena_feed(this.handle, this.core.copyIn(frame), frame.length);
  }

  ended(): boolean {
    return this.core.module._arena_ended(this.handle) === 1;
  }
  error(): string {
    return this.core.text(this.core.module._arena_error(this.handle));
  }

  private out(size: number): Uint8Array {
    return this.core.bytes(this.core.module._arena_out(this.handle), size);
  }
  /** The Hello; `match` joins that match, `mode` joins or creates one of that mode (both
   *  empty: the server's default match). */
  hello(name: string, token: string, match = '', mode = ''): Uint8Array {
    return this.out(
      this.core.withStrings([name, token, match, mode], (n, t, m, d) => this.core.module._arena_hello_to(this.handle, n, t, m, d)),
    );
  }
  /** Numbers and predicts the input; an empty frame before the Welcome, after the end, for
   *  a spectator, and for a tick the input pacing leaves out (inputsLeftOut counts those):
   *  the server kept too many inputs waiting, so this tick's is not sent (protocol/README.md,
   *  "Input pacing"); the next one carries the next sequence. Send only non-empty frames. */
  input(thrust: number, turn: number, buttons: number): Uint8Array {
    return this.out(this.core.module._arena_input(this.handle, thrust, turn, buttons));
  }
  /** The moment of the world shown now (the interpolated view's tick, and `fraction`/256 of a
   *  tick past it), which every input from now on carries (Input.view_tick, view_fraction) for
   *  the server's lag compensation (docs/LAG_COMPENSATION.md). Never told (or tick 0): the
   *  inputs carry the newest snapshot's tick. */
  setViewMoment(tick: number, fraction: number): void {
    const t = Number.isFinite(tick) ? Math.max(0, Math.min(0xffffffff, Math.floor(tick))) : 0;
    const f = Number.isFinite(fraction) ? Math.max(0, Math.min(255, Math.floor(fraction))) : 0;
    this.core.module._arena_set_view_moment(this.handle, t, f);
  }
  /** clientTime: an integer (e.g. microseconds), echoed by the server's Pong. */
  ping(clientTime: number): Uint8Array {
    return this.out(this.core.module._arena_ping(this.handle, Math.max(0, Math.floor(clientTime))));
  }
  bye(reason: string): Uint8Array {
    return this.out(this.core.withStrings([reason], (r) => this.core.module._arena_bye(this.handle, r)));
  }

  get playerId(): number {
    return this.core.module._arena_player_id(this.handle);
  }
  get entityId(): number {
    return this.core.module._arena_entity_id(this.handle);
  }
  get tickRate(): number {
    return this.core.module._arena_tick_rate(this.handle);
  }
  get snapshotRate(): number {
    return this.core.module._arena_snapshot_rate(this.handle);
  }
  /** The world's bounds (from the Welcome's config): whether bodies wrap around, and its size. */
  get world(): { wraps: boolean; width: number; height: number } {
    const m = this.core.module;
    return { wraps: m._arena_world_wraps(this.handle) === 1, width: m._arena_world_width(this.handle), height: m._arena_world_height(this.handle) };
  }
  get viewTick(): number {
    return this.core.module._arena_view_tick(this.handle);
  }
  get viewAck(): number {
    return this.core.module._arena_view_ack(this.handle);
  }
  get lastSequence(): number {
    return this.core.module._arena_last_sequence(this.handle);
  }
  get deltaAck(): number {
    return this.core.module._arena_delta_ack(this.handle);
  }
  /** Ticks whose input the pacing left out (input() returned an empty frame for them). */
  get inputsLeftOut(): number {
    return this.core.module._arena_inputs_left_out(this.handle);
  }
  /** Why the newest snapshot's delta did not decode (a server bug); '' when it did. */
  deltaProblem(): string {
    return this.core.text(this.core.module._arena_delta_problem(this.handle));
  }

  /** The newest snapshot's bodies, by increasing id. */
  view(): BodyState[] {
    const m = this.core.module;
    return this.core.readBodies(m._arena_view(this.handle), m._arena_view_count(this.handle));
  }
  /** The raw 32-byte BodyStates of view(), for exact comparisons. */
  viewBytes(): Uint8Array {
    const m = this.core.module;
    return this.core.bytes(m._arena_view(this.handle), 32 * m._arena_view_count(this.handle));
  }
  /** Shapes of the newest view's bodies held by this client, by id. */
  shapes(): Shape[] {
    const m = this.core.module;
    return this.core.readShapes(m._arena_shapes(this.handle), m._arena_shape_count(this.handle));
  }
  statics(): StaticBody[] {
    const m = this.core.module;
    return this.core.readStatics(m._arena_statics(this.handle), m._arena_static_count(this.handle));
  }
  /** The own body predicted for the last input; null before a snapshot placed it. */
  predicted(): PredictedBody | null {
    const p = this.core.module._arena_predicted(this.handle);
    if (p === 0) return null;
    const d = this.core.view(p, 24);
    return {
      x: d.getFloat32(0, true),
      y: d.getFloat32(4, true),
      vx: d.getFloat32(8, true),
      vy: d.getFloat32(12, true),
      angle: d.getFloat32(16, true),
      angularVelocity: d.getFloat32(20, true),
    };
  }
  /** The own bullets where the prediction has them now: confirmed ones (moved on from the
   *  newest snapshot by the world's own steps) by increasing bodyId, then predicted ones. */
  ownBullets(): OwnBullet[] {
    const m = this.core.module;
    const p = m._arena_own_bullets(this.handle);
    const count = m._arena_own_bullet_count(this.handle);
    const d = this.core.view(p, 24 * count);
    const out: OwnBullet[] = [];
    for (let i = 0; i < count; ++i) {
      const at = 24 * i;
      out.push({
        bodyId: d.getUint32(at, true),
        sequence: d.getUint32(at + 4, true),
        x: d.getFloat32(at + 8, true),
        y: d.getFloat32(at + 12, true),
        vx: d.getFloat32(at + 16, true),
        vy: d.getFloat32(at + 20, true),
      });
    }
    return out;
  }
  /** The raw bytes of ownBullets() (24 each), for exact comparisons. */
  ownBulletsBytes(): Uint8Array {
    const m = this.core.module;
    const p = m._arena_own_bullets(this.handle);
    return this.core.bytes(p, 24 * m._arena_own_bullet_count(this.handle));
  }
  /** The 24 raw bytes of predicted(), for exact comparisons; null as predicted(). */
  predictedBytes(): Uint8Array | null {
    const p = this.core.module._arena_predicted(this.handle);
    return p === 0 ? null : this.core.bytes(p, 24);
  }
  /** Metres between the position predicted for the newest snapshot's acknowledged input and
   *  the server's; null when that snapshot measured none. */
  predictionError(): number | null {
    const e = this.core.module._arena_prediction_error(this.handle);
    return Number.isNaN(e) ? null : e;
  }
}
