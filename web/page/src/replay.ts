// The replay page (/replay): plays an arena-server --record file with the server's world in
// WebAssembly (the SDK's ReplayPlayer), drawn as the game page draws a match. The recording
// comes from ?src=URL or from a file the viewer opens. Play, pause, speed 0.25x to 8x and a
// scrub bar (seeking back re-simulates from the start); every recorded hash is compared as
// the world reaches its tick, and the first mismatch stops the replay with both hashes shown.
// window.arenaReplay holds the figures, for tests and the console.
import { Core, ReplayPlayer } from './arena-sdk.mjs';
import { Body, Painter } from './draw.js';

interface ReplayState {
  /** Where the recording came from: the ?src URL or the file's name. */
  source: string;
  loaded: boolean;
  playing: boolean;
  speed: number;
  tick: number;
  startTick: number;
  endTick: number;
  /** Computed at `tick`, and the recording's own for it ('' when it holds none there). */
  hash: string;
  recordedHash: string;
  hashesChecked: number;
  hashesTotal: number;
  /** The first mismatch or the file's problem; '' while every hash matched. */
  error: string;
  cutShort: string;
  frames: number;
}

declare global {
  interface Window {
    arenaReplay: ReplayState;
  }
}

function el<T extends HTMLElement>(id: string): T {
  const e = document.getElementById(id);
  if (!e) throw new Error(`the page has no #${id}`);
  return e as T;
}

// "tick T: hash mismatch: expected E, actual A" (web/sdk/core/c_api.cpp) as a sentence.
function describeFailure(error: string): string {
  const m = /^tick (\d+): hash mismatch: expected ([0-9a-f]+), actual ([0-9a-f]+)$/.exec(error);
  if (!m) return `replay failed: ${error}`;
  return `hash MISMATCH at tick ${m[1]}: the recording has ${m[2]}, this replay computed ${m[3]}`;
}

async function main(): Promise<void> {
  const painter = new Painter(el<HTMLCanvasElement>('game'));
  const playButton = el<HTMLButtonElement>('play');
  const speedSelect = el<HTMLSelectElement>('speed');
  const scrub = el<HTMLInputElement>('scrub');
  const tickText = el('tick');
  const hashesText = el('hashes');
  const sourceText = el('source');
  const status = el('status');
  const state: ReplayState = {
    source: '', loaded: false, playing: false, speed: Number(speedSelect.value), tick: 0, startTick: 0, endTick: 0, hash: '', recordedHash: '',
    hashesChecked: 0, hashesTotal: 0, error: '', cutShort: '', frames: 0,
  };
  window.arenaReplay = state;
  const setStatus = (text: string) => {
    status.textContent = text;
    status.hidden = text === '';
  };

  const core = await Core.load();
  let player: ReplayPlayer | null = null;
  let carry = 0; // ticks owed to the clock, below one
  let last = 0;

  const show = () => {
    if (!player) return;
    state.tick = player.tick;
    state.hash = player.hash;
    state.recordedHash = player.recordedHash;
    state.hashesChecked = player.hashesChecked;
    state.hashesTotal = player.hashesTotal;
    state.error = player.error;
    tickText.textContent = `tick ${state.tick - state.startTick} / ${state.endTick - state.startTick}`;
    if (document.activeElement !== scrub) scrub.value = String(state.tick);
    playButton.textContent = state.playing ? 'pause' : state.tick >= state.endTick ? 'replay' : 'play';
    if (state.error !== '') {
      hashesText.className = 'failed';
      hashesText.textContent = `hashes verified: ${state.hashesChecked - 1}/${state.hashesTotal} · ${describeFailure(state.error)}`;
    } else {
      hashesText.className = 'verified';
      const at = state.recordedHash !== '' ? ` · tick ${state.tick}: ${state.hash} verified` : '';
      const end = state.tick >= state.endTick ? (state.cutShort !== '' ? ' · recording cut short here' : ' · final hash verified') : '';
      hashesText.textContent = `hashes verified: ${state.hashesChecked}/${state.hashesTotal}${at}${end}`;
    }
    const world = player.world;
    const bodies: Body[] = player.bodies().map((b) => ({ ...b, predicted: false }));
    const span = Math.max(world.width, world.height) || 100;
    painter.frame(world, 0, { x: world.width / 2, y: world.height / 2 }, [], bodies, [], performance.now(), span);
    ++state.frames;
  };

  const pause = () => {
    state.playing = false;
    show();
  };

  const frame = (now: number) => {
    if (player && state.playing) {
      carry += ((now - last) / 1000) * player.tickRate * state.speed;
      const ticks = Math.floor(carry);
      carry -= ticks;
      if (ticks > 0 && !player.step(ticks)) state.playing = false;
      if (player.tick >= state.endTick) state.playing = false;
      show();
    }
    last = now;
    requestAnimationFrame(frame);
  };
  requestAnimationFrame(frame);

  const open = (bytes: Uint8Array, source: string) => {
    player?.close();
    player = null;
    state.loaded = false;
    state.playing = false;
    state.source = source;
    sourceText.textContent = source;
    try {
      player = ReplayPlayer.open(core, bytes);
    } catch (e) {
      hashesText.className = 'failed';
      hashesText.textContent = `cannot replay ${source}: ${e instanceof Error ? e.message : String(e)}`;
      state.error = hashesText.textContent;
      return;
    }
    state.startTick = player.startTick;
    state.endTick = player.endTick;
    state.cutShort = player.cutShort;
    scrub.min = String(state.startTick);
    scrub.max = String(state.endTick);
    scrub.disabled = false;
    playButton.disabled = false;
    state.loaded = true;
    setStatus('');
    show();
  };

  playButton.addEventListener('click', () => {
    if (!player) return;
    if (state.playing) return pause();
    if (player.tick >= state.endTick) player.seek(state.startTick);
    carry = 0;
    state.playing = player.error === '';
    show();
  });
  speedSelect.addEventListener('change', () => {
    state.speed = Number(speedSelect.value);
  });
  scrub.addEventListener('input', () => {
    if (!player) return;
    player.seek(Number(scrub.value));
    show();
  });
  el<HTMLInputElement>('file').addEventListener('change', async (e) => {
    const file = (e.target as HTMLInputElement).files?.[0];
    if (file) open(new Uint8Array(await file.arrayBuffer()), file.name);
  });

  const src = new URLSearchParams(location.search).get('src');
  if (src) {
    setStatus(`loading ${src}…`);
    const response = await fetch(src);
    if (!response.ok) throw new Error(`${src}: HTTP ${response.status}`);
    open(new Uint8Array(await response.arrayBuffer()), src);
  } else {
    setStatus('open a recording (an arena-server --record file)');
  }
}

main().catch((e: unknown) => {
  const message = e instanceof Error ? e.message : String(e);
  if (window.arenaReplay) window.arenaReplay.error = message;
  const status = document.getElementById('status');
  if (status) {
    status.textContent = `cannot start: ${message}`;
    status.hidden = false;
  }
});
