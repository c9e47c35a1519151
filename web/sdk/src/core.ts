// The client core in WebAssembly (web/sdk/core/, the server's own C++), behind a typed API.
// Frames are copied into the module's memory, handled there (verified, Welcome-checked,
// delta-decoded, predicted) and the results read back from where the C API points.
import createArenaCore, { CoreModule, CoreModuleOptions } from './arena_core.mjs';

export type { CoreModuleOptions };

/** One body as the server describes it (BodyState): metres, m/s, radians, rad/s. */
export interface BodyState {
  id: number;
  owner: number;
  x: number;
  y: number;
  vx: number;
  vy: number;
  angle: number;
  angularVelocity: number;
}

/** How a body is drawn (BodyShape and its vertices, in the body's frame). */
export interface Shape {
  id: number;
  /** The game's tag: Asteroids says ship 1, rock 2, bullet 3; 0 = a plain body. */
  kind: number;
  /** circle 0, capsule 1, polygon 2, segment 3 (protocol ShapeType). */
  type: number;
  radius: number;
  /** x0, y0, x1, y1, ... */
  vertices: number[];
}

export interface StaticBody {
  x: number;
  y: number;
  angle: number;
  shape: Shape;
}

/** protocol Payload values that feed() returns. */
export const Payload = { NONE: 0, Hello: 1, Welcome: 2, Reject: 3, Input: 4, Snapshot: 5, Ping: 6, Pong: 7, Bye: 8 } as const;

const BODY_BYTES = 32;
const SHAPE_BYTES = 76;
const STATIC_BYTES = 88;

/** The loaded module; one per page is enough (sessions and replays share it). */
export class Core {
  readonly module: CoreModule;
  private scratch = 0;
  private scratchSize = 0;

  private constructor(module: CoreModule) {
    this.module = module;
  }

  /** Loads arena_core.wasm: in a browser from beside arena_core.mjs (or options.locateFile),
   *  anywhere from options.wasmBinary. */
  static async load(options: CoreModuleOptions = {}): Promise<Core> {
    return new Core(await createArenaCore(options));
  }


  /** Copies bytes into module memory; the pointer is valid until the next copy. */
  copyIn(bytes: Uint8Array): number {
    if (bytes.length > this.scratchSize) {
      if (this.scratch !== 0) this.module._free(this.scratch);
      this.scratchSize = Math.max(bytes.length, 2 * this.scratchSize, 4096);
      this.scratch = this.module._malloc(this.scratchSize);
    }
    this.module.HEAPU8.set(bytes, this.scratch);
    return this.scratch;
  }

  /** Runs f with a NUL-terminated UTF-8 copy of each string, freed afterwards. */
  withStrings<T>(texts: string[], f: (...pointers: number[]) => T): T {
    const pointers = texts.map((t) => {
      const size = this.module.lengthBytesUTF8(t) + 1;
      const p = this.module._malloc(size);
      this.module.stringToUTF8(t, p, size);
      return p;
    });
    try {
      return f(...pointers);
    } finally {
      for (const p of pointers) this.module._free(p);
    }
  }

  text(pointer: number): string {
    return this.module.UTF8ToString(pointer);
  }

  bytes(pointer: number, size: number): Uint8Array {
    return this.module.HEAPU8.slice(pointer, pointer + size);
  }

  view(pointer: number, size: number): DataView {
    return new DataView(this.module.HEAPU8.buffer, pointer, size);
  }

  readBodies(pointer: number, count: number): BodyState[] {
    const d = this.view(pointer, count * BODY_BYTES);
    const out: BodyState[] = new Array(count);
    for (let i = 0; i < count; ++i) {
      const o = i * BODY_BYTES;
      out[i] = {
        id: d.getUint32(o, true),
        owner: d.getUint32(o + 4, true),
        x: d.getFloat32(o + 8, true),
        y: d.getFloat32(o + 12, true),
        vx: d.getFloat32(o + 16, true),
        vy: d.getFloat32(o + 20, true),
        angle: d.getFloat32(o + 24, true),
        angularVelocity: d.getFloat32(o + 28, true),
      };
    }
    return out;
  }

  readShape(d: DataView, o: number): Shape {
    const count = d.getUint8(o + 6);
    const vertices: number[] = [];
    for (let v = 0; v < 2 * count; ++v) vertices.push(d.getFloat32(o + 12 + 4 * v, true));
    return { id: d.getUint32(o, true), kind: d.getUint8(o + 4), type: d.getUint8(o + 5), radius: d.getFloat32(o + 8, true), vertices };
  }

  readShapes(pointer: number, count: number): Shape[] {
    const d = this.view(pointer, count * SHAPE_BYTES);
    const out: Shape[] = [];
    for (let i = 0; i < count; ++i) out.push(this.readShape(d, i * SHAPE_BYTES));
    return out;
  }

  readStatics(pointer: number, count: number): StaticBody[] {
    const d = this.view(pointer, count * STATIC_BYTES);
    const out: StaticBody[] = [];
    for (let i = 0; i < count; ++i) {
      const o = i * STATIC_BYTES;
      out.push({ x: d.getFloat32(o, true), y: d.getFloat32(o + 4, true), angle: d.getFloat32(o + 8, true), shape: this.readShape(d, o + 12) });
    }
    return out;
  }

  /** Replays a recording (a server's --record file) with the world compiled to WebAssembly. */
  replay(recording: Uint8Array, until?: number): ReplayResult {
    const path = '/recording.arpl';
    this.module.FS.writeFile(path, recording);
    try {
      const handle = this.withStrings([path], (p) => this.module._arena_replay_open(p));
      if (handle === 0) return { ok: false, error: this.text(this.module._arena_replay_open_error()), hashes: [], finalTick: 0, finalHash: '', hashesChecked: 0, bodies: [] };
      try {
        const ok = this.module._arena_replay_run(handle, until ?? -1) === 1;
        const dump = this.text(this.module._arena_replay_dump(handle));
        const hashes = dump
          .split('\n')
          .slice(1)
          .filter((line) => line !== '')
          .map((line) => {
            const [tick, hash] = line.split(',');
            return { tick: Number(tick), hash };
          });
        const bodiesAt = this.module._arena_replay_bodies(handle);
        return {
          ok,
          error: this.text(this.module._arena_replay_error(handle)),
          hashes,
          finalTick: this.module._arena_replay_final_tick(handle),
          finalHash: this.text(this.module._arena_replay_final_hash(handle)),
          hashesChecked: this.module._arena_replay_hashes_checked(handle),
          bodies: this.readBodies(bodiesAt, this.module._arena_replay_body_count(handle)),
        };
      } finally {
        this.module._arena_replay_free(handle);
      }
    } finally {
      this.module.FS.unlink(path);
    }
  }
}

export interface ReplayResult {
  /** Every recorded hash matched and the recording was read to its end (or to `until`). */
  ok: boolean;
  /** Why not, when not ok: a file problem, or the first hash mismatch. */
  error: string;
  /** The world's hash at the start tick and after every step: 16 hex digits each, as
   *  `arena-replay --dump-hashes` prints them. */
  hashes: { tick: number; hash: string }[];
  finalTick: number;
  /** The final state hash (world and rules), as arena-replay's final_hash. */
  finalHash: string;
  hashesChecked: number;
  /** The replayed world's bodies at the end. */
  bodies: BodyState[];
}
