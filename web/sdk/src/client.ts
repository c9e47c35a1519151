// What a game developer uses: connect(url, name, token), events, input(), stateAt(); with
// {spectate: true} the same client watches the match without a body. The
// WebSocket carries one protocol frame per binary message; every frame goes through the
// WebAssembly core first (verification, Welcome checks, delta decoding, prediction), then
// the SDK reads the rest (names, scoreboard, game events) with the generated TypeScript.
import { BodyState, Core, CoreModuleOptions, Payload, Shape, StaticBody } from './core.js';
import { Interpolator, InterpolationOptions } from './interpolation.js';
import { ByeFields, GameEvent, GameRecord, GameValue, PlayerLine, WelcomeFields, readBye, readMessage, readPong, readReject, readSnapshotExtras, readWelcome } from './messages.js';
import { CoreSession, OwnBullet } from './session.js';
import { CorrectionSmoother, SmoothingOptions } from './smoothing.js';

/** The part of the browser's WebSocket the SDK uses; tests hand in a fake one. */
export interface SocketLike {
  binaryType: string;
  send(data: Uint8Array): void;
  close(code?: number, reason?: string): void;
  onopen: ((ev: unknown) => void) | null;
  onmessage: ((ev: { data: unknown }) => void) | null;
  onclose: ((ev: unknown) => void) | null;
  onerror: ((ev: unknown) => void) | null;
}

/** The WebSocket close code of a session the SDK ends because the server broke the protocol. */
export const PROTOCOL_ERROR_CLOSE_CODE = 4002;

export interface ConnectOptions {
  /** A loaded core to share; otherwise one is loaded with coreOptions. */
  core?: Core;
  coreOptions?: CoreModuleOptions;
  /** Makes the socket (default: new WebSocket(url)). */
  socket?: (url: string) => SocketLike;
  /** The clock, ms (default performance.now()). */
  now?: () => number;
  /** Send inputs at the tick rate from a timer (default true); false: call pump(now) yourself. */
  autoPump?: boolean;
  /** Ask for delta snapshots (default true). */
  deltaSnapshots?: boolean;
  /** Watch the match without a body (Hello.spectator, default false): the server sends the
   *  whole world and the scoreboard; input() does nothing and stateAt().own is null. */
  spectate?: boolean;
  /** Join the match with this id (Hello.match; the lobby lists them, docs/MATCHES.md). */
  match?: string;
  /** Join the fullest open match of this mode with a seat, or create one (Hello.mode). With
   *  neither, the server's default match. */
  mode?: string;
  interpolation?: Partial<InterpolationOptions>;
  smoothing?: SmoothingOptions;
}

export interface Welcome extends WelcomeFields {
  statics: StaticBody[];
  world: { wraps: boolean; width: number; height: number };
}

export interface SnapshotEvent {
  tick: number;
  ack: number;
  bodies: BodyState[];
  players: PlayerLine[];
  /** Metres: the prediction of the acknowledged input against the server's answer. */
  predictionError: number | null;
}

/** A body to draw. */
export interface DrawBody extends BodyState {
  shape?: Shape;
  /** The game's tag from the shape (Asteroids: ship 1, rock 2, bullet 3). */
  kind: number;
  /** The own body, predicted (and its corrections smoothed); the others are interpolated. */
  predicted: boolean;
}

export interface RenderState {
  /** The own ship and the own bullets the server confirmed are drawn where the prediction has
   *  them now (predicted: true), the other bodies interpolated. */
  bodies: DrawBody[];
  own: DrawBody | null;
  /** The own shots predicted and not yet in a snapshot (Asteroids), where they are now: a
   *  bullet appears as its shot is fired, not a round trip later. */
  shots: OwnBullet[];
  statics: StaticBody[];
  /** The server time drawn for the interpolated bodies, ms. */
  serverTime: number;
  extrapolated: number;
  /** The moment of the world drawn (the interpolated bodies'), as a tick and 1/256 ticks past
   *  it: what the inputs sent from now on carry for lag compensation; null before a snapshot. */
  view: ViewMoment | null;
}

/** A moment of the server's world: `tick` and `fraction`/256 of a tick past it. */
export interface ViewMoment {
  tick: number;
  fraction: number;
}

/** An Input the client sent (the 'input' event): its sequence, its buttons, and the moment of
 *  the world it carried (the view drawn last; before any draw, the newest snapshot's tick). */
export interface SentInput extends ViewMoment {
  sequence: number;
  buttons: number;
}

interface Events {
  welcome: Welcome;
  snapshot: SnapshotEvent;
  players: { players: PlayerLine[]; names: Map<number, string> };
  event: GameEvent;
  /** One of the game's declared events (Welcome.game.events[kind]), each once, in order. */
  record: GameRecord;
  pong: { rtt: number; serverTick: number };
  /** Each Input as it goes out (not the ticks the pacing leaves out). */
  input: SentInput;
  bye: ByeFields;
}
type Handler<T> = (value: T) => void;

export class ArenaClient {
  readonly session: CoreSession;
  private readonly socket: SocketLike;
  private readonly now: () => number;
  private readonly options: ConnectOptions;
  private handlers: { [K in keyof Events]?: Handler<Events[K]>[] } = {};
  private controls = { thrust: 0, turn: 0, buttons: 0 };
  private welcome: Welcome | null = null;
  private interpolator: Interpolator | null = null;
  private smoother: CorrectionSmoother | null = null;
  private tickStart = 0;
  private ticksSent = 0;
  private lastPing = -Infinity;
  private timer: ReturnType<typeof setInterval> | null = null;
  private shapes = new Map<number, { shape: Shape; seen: number }>();
  private snapshots = 0;
  private lastEvent = 0;
  private done = false;
  private ownInView = false;
  // The moment of the view stateAt drew last: what the player saw when pressing the keys.
  private drawnMoment: ViewMoment | null = null;
  /** Round-trip time of the last Pong, ms. */
  rtt: number | null = null;
  readonly players = new Map<number, PlayerLine & { name: string }>();
  /** The game's declared values (Welcome.game): each player's and each team's, in the
   *  manifest's field order, as of the newest snapshot. */
  readonly values = new Map<number, number[]>();
  readonly teamValues = new Map<number, number[]>();
  private lastRecord = 0;

  constructor(core: Core, socket: SocketLike, name: string, token: string, options: ConnectOptions) {
    this.options = options;
    this.now = options.now ?? (() => performance.now());
    this.session = new CoreSession(core, options.deltaSnapshots ?? true, options.spectate ?? false);
    this.socket = socket;
    socket.binaryType = 'arraybuffer';
    socket.onopen = () => socket.send(this.session.hello(name, token, options.match ?? '', options.mode ?? ''));
    socket.onmessage = (ev) => this.receive(ev.data);
    socket.onclose = () => this.finish({ reason: 'connection closed', matchOver: false, winner: 0, scoreboard: [] });
    socket.onerror = () => this.finish({ reason: 'connection failed', matchOver: false, winner: 0, scoreboard: [] });
  }

  on<K extends keyof Events>(event: K, handler: Handler<Events[K]>): this {
    (this.handlers[event] ??= [] as never[]).push(handler as never);
    return this;
  }
  off<K extends keyof Events>(event: K, handler: Handler<Events[K]>): this {
    const list = this.handlers[event] as Handler<Events[K]>[] | undefined;
    if (list) this.handlers[event] = list.filter((h) => h !== handler) as never;
    return this;
  }
  private emit<K extends keyof Events>(event: K, value: Events[K]): void {
    for (const h of (this.handlers[event] as Handler<Events[K]>[] | undefined) ?? []) h(value);
  }

  /** Whether this client watches the match (options.spectate): it has no body and sends no input. */
  get spectating(): boolean {
    return this.session.spectator;
  }

  /** The controls from now on: thrust and turn in [−1, 1], buttons bit 0 the impulse (fire).
   *  They are sent once per server tick (pump), as the server consumes them. A spectator's are
   *  ignored: the server refuses its Inputs. */
  input(thrust: number, turn: number, buttons: number): void {
    if (this.spectating) return;
    const clamp = (v: number) => (Number.isFinite(v) ? Math.max(-1, Math.min(1, v)) : 0);
    this.controls = { thrust: clamp(thrust), turn: clamp(turn), buttons: buttons & 0xff };
  }

  /** Sends the inputs due by `now` (one per tick since the Welcome, at most 4 at once: a tab
   *  that slept does not send a burst) and a Ping once a second. */
  pump(now: number = this.now()): void {
    if (!this.welcome || this.done) return;
    const due = Math.floor(((now - this.tickStart) * this.welcome.tickRate) / 1000);
    if (due - this.ticksSent > 4) this.ticksSent = due - 4;
    // A spectator sends only the Pings: they are what keeps it from the server's idle timeout.
    if (this.spectating) this.ticksSent = due;
    while (this.ticksSent < due) {
      ++this.ticksSent;
      const { thrust, turn, buttons } = this.controls;
      // The moment of the world the player was looking at (lag compensation): before any
      // draw, nothing is told and the core puts the newest snapshot's tick.
      const moment = this.drawnMoment;
      if (moment) this.session.setViewMoment(moment.tick, moment.fraction);
      const frame = this.session.input(thrust, turn, buttons);
      // Empty when there is nothing to send this tick: a tick the input pacing leaves out (the
      // server kept too many inputs waiting; the next one carries the next sequence). The
      // tick is spent all the same, so that the queue at the server is one shorter.
      if (frame.length > 0) {
        this.socket.send(frame);
        const sent = moment ?? { tick: this.session.viewTick, fraction: 0 };
        this.emit('input', { sequence: this.session.lastSequence, buttons, tick: sent.tick, fraction: sent.fraction });
      }
    }
    if (now - this.lastPing >= 1000) {
      this.lastPing = now;
      this.socket.send(this.session.ping(Math.round(now * 1000)));
    }
  }

  /** What to draw at `renderTime` (ms, the clock of options.now): the own body predicted and
   *  smoothed, every other body interpolated from the snapshot buffer. */
  stateAt(renderTime: number = this.now()): RenderState {
    if (!this.welcome || !this.interpolator) return { bodies: [], own: null, shots: [], statics: [], serverTime: 0, extrapolated: 0, view: null };
    const sampled = this.interpolator.sample(renderTime);
    const view = this.interpolator.size > 0 ? momentOf(sampled.moment, this.welcome.tickRate) : null;
    if (view) this.drawnMoment = view;
    const own = this.session.entityId;
    const bodies: DrawBody[] = [];
    // The own bullets as the prediction has them now: drawn from the snapshots, they would lag
    // the ship that fired them by the round trip and the interpolation delay.
    const bullets = this.session.ownBullets();
    const confirmed = new Map<number, OwnBullet>();
    const shots: OwnBullet[] = [];
    for (const b of bullets) {
      if (b.bodyId === 0) shots.push(b);
      else confirmed.set(b.bodyId, b);
    }
    for (const b of sampled.bodies) {
      if (b.id === own) continue;
      const now = confirmed.get(b.id);
      if (!now) {
        bodies.push(this.decorate(b, false));
        continue;
      }
      bodies.push(this.decorate({ ...b, x: now.x, y: now.y, vx: now.vx, vy: now.vy }, true));
      confirmed.delete(b.id);
    }
    // Confirmed bullets younger than the interpolated time: in no sampled snapshot yet.
    for (const b of confirmed.values())
      bodies.push(this.decorate({ id: b.bodyId, owner: 0, x: b.x, y: b.y, vx: b.vx, vy: b.vy, angle: 0, angularVelocity: 0 }, true));
    let ownBody: DrawBody | null = null;
    const p = this.session.predicted();
    // Drawn only while the server shows it: after the ship is lost, the prediction is stale.
    if (p && this.smoother && this.ownInView) {
      const drawn = this.smoother.apply(p, renderTime);
      ownBody = this.decorate({ id: own, owner: this.session.playerId, ...drawn }, true);
      bodies.push(ownBody);
    }
    return { bodies, own: ownBody, shots, statics: this.welcome.statics, serverTime: sampled.serverTime, extrapolated: sampled.extrapolated, view };
  }

  /** The moment of the view stateAt drew last, which the next inputs carry; null before any draw. */
  get viewMoment(): ViewMoment | null {
    return this.drawnMoment;
  }

  /** Ticks whose input was left out because the server kept too many waiting (input
   *  pacing, protocol/README.md): a figure for a game's network display. */
  get inputsLeftOut(): number {
    return this.session.inputsLeftOut;
  }

  /** Says Bye and closes. */
  close(reason = 'bye'): void {
    if (!this.done && this.welcome) this.socket.send(this.session.bye(reason));
    this.socket.close(1000, reason);
    this.finish({ reason, matchOver: false, winner: 0, scoreboard: [] });
  }

  /** The snapshot buffer's delay and the jitter it measures, ms. */
  get buffer(): { delay: number; jitter: number; size: number } {
    return { delay: this.interpolator?.delay ?? 0, jitter: this.interpolator?.jitter ?? 0, size: this.interpolator?.size ?? 0 };
  }
  get smoothing(): CorrectionSmoother | null {
    return this.smoother;
  }

  private decorate(b: BodyState, predicted: boolean): DrawBody {
    const shape = this.shapes.get(b.id)?.shape;
    return { ...b, shape, kind: shape?.kind ?? 0, predicted };
  }

  private receive(data: unknown): void {
    if (this.done) return;
    const frame = data instanceof ArrayBuffer ? new Uint8Array(data) : data instanceof Uint8Array ? data : null;
    if (frame === null) return this.fail('a text message from the server');
    const now = this.now();
    const before = this.session.predicted();
    const type = this.session.feed(frame);
    if (type === Payload.NONE) return this.fail(this.session.error());
    const message = readMessage(frame);
    switch (type) {
      case Payload.Welcome: {
        const world = this.session.world;
        this.welcome = { ...readWelcome(message), statics: this.session.statics(), world };
        const wrap = world.wraps ? { width: world.width, height: world.height } : undefined;
        this.interpolator = new Interpolator({ interval: 1000 / this.welcome.snapshotRate, tickRate: this.welcome.tickRate, wrap, ...this.options.interpolation });
        this.smoother = new CorrectionSmoother({ wrap, ...this.options.smoothing });
        this.tickStart = now;
        this.emit('welcome', this.welcome);
        if (this.options.autoPump ?? true) this.timer = setInterval(() => this.pump(), 1000 / this.welcome.tickRate / 2);
        return;
      }
      case Payload.Snapshot:
        return this.onSnapshot(message, before, now);
      case Payload.Pong: {
        const pong = readPong(message);
        this.rtt = now - pong.clientTime / 1000;
        this.emit('pong', { rtt: this.rtt, serverTick: pong.serverTick });
        return;
      }
      case Payload.Bye:
        return this.finish(readBye(message));
      case Payload.Reject:
        return this.finish(readReject(message));
    }
  }

  private onSnapshot(message: ReturnType<typeof readMessage>, before: ReturnType<CoreSession['predicted']>, now: number): void {
    const after = this.session.predicted();
    if (before && after && this.smoother) this.smoother.correct(before, after);
    const extras = readSnapshotExtras(message);
    for (const [id, name] of extras.names) {
      const line = this.players.get(id);
      if (line) line.name = name;
      else this.players.set(id, { playerId: id, score: 0, kills: 0, deaths: 0, shots: 0, hits: 0, lives: 0, state: 0, name });
    }
    for (const p of extras.players) this.players.set(p.playerId, { ...p, name: this.players.get(p.playerId)?.name ?? '' });
    if (extras.players.length > 0 || extras.names.size > 0) this.emit('players', { players: extras.players, names: extras.names });
    // Events repeat until acknowledged: each is taken once, by sequence.
    for (const e of extras.events) {
      if (e.sequence <= this.lastEvent) continue;
      this.lastEvent = e.sequence;
      this.emit('event', e);
    }
    const game = this.welcome?.game ?? null;
    const keep = (into: Map<number, number[]>, list: GameValue[], fields: number) => {
      for (const v of list) {
        if (v.field >= fields) continue;  // not in the manifest: the server's bug, not trusted
        const held = into.get(v.owner) ?? new Array<number>(fields).fill(0);
        held[v.field] = v.value;
        into.set(v.owner, held);
      }
    };
    keep(this.values, extras.playerValues, game?.playerFields.length ?? 0);
    keep(this.teamValues, extras.teamValues, game?.teamFields.length ?? 0);
    if (extras.playerValues.length > 0 || extras.teamValues.length > 0) this.emit('players', { players: extras.players, names: extras.names });
    for (const r of extras.records) {
      if (r.sequence <= this.lastRecord) continue;
      this.lastRecord = r.sequence;
      this.emit('record', r);
    }
    if (this.session.deltaProblem() !== '') return;  // its view was skipped: the next one is full
    ++this.snapshots;
    for (const s of this.session.shapes()) this.shapes.set(s.id, { shape: s, seen: this.snapshots });
    const bodies = this.session.view();
    this.ownInView = bodies.some((b) => b.id === this.session.entityId);
    for (const b of bodies) {
      const s = this.shapes.get(b.id);
      if (s) s.seen = this.snapshots;
    }
    // Shapes of bodies gone for longer than the buffer can show them are dropped.
    for (const [id, s] of this.shapes) if (this.snapshots - s.seen > 32) this.shapes.delete(id);
    this.interpolator?.push(this.session.viewTick, bodies, now);
    this.emit('snapshot', { tick: this.session.viewTick, ack: this.session.viewAck, bodies, players: extras.players, predictionError: this.session.predictionError() });
  }

  private fail(reason: string): void {
    // Browsers let a page close with 1000 or 3000-4999 only (any other code throws
    // InvalidAccessError, and the bye below would never be emitted): 4002 is 1002's
    // "protocol error" in the range kept for applications.
    this.socket.close(PROTOCOL_ERROR_CLOSE_CODE, 'protocol error');
    this.finish({ reason, matchOver: false, winner: 0, scoreboard: [] });
  }

  private finish(bye: ByeFields): void {
    if (this.done) return;
    this.done = true;
    if (this.timer !== null) clearInterval(this.timer);
    this.timer = null;
    this.emit('bye', bye);
  }
}

/** A server time (ms) as a tick and 1/256 ticks past it, rounded down; never below tick 0. */
export function momentOf(serverTime: number, tickRate: number): ViewMoment {
  const ticks = Math.max(0, (serverTime * tickRate) / 1000);
  let tick = Math.floor(ticks);
  let fraction = Math.floor((ticks - tick) * 256);
  if (fraction > 255) { ++tick; fraction = 0; }
  return { tick, fraction };
}

/** Connects to an Arena server's WebSocket endpoint (ws://host:http-port/ws) as `name`. */
export async function connect(url: string, name: string, token = '', options: ConnectOptions = {}): Promise<ArenaClient> {
  const core = options.core ?? (await Core.load(options.coreOptions));
  const socket = options.socket ? options.socket(url) : (new WebSocket(url) as unknown as SocketLike);
  return new ArenaClient(core, socket, name, token, options);
}
