// The keyboard as the game's controls: arrows turn and thrust; the game's buttons on the keys
// its manifest declares (Welcome.game.inputs: soccer's kick on Space), else space fires and
// shift boosts. Input.buttons bits: 0 the world's impulse (the boost), the rest the game's.

export const BUTTON_BOOST = 1 << 0;
export const BUTTON_FIRE = 1 << 1;

const GAME_KEYS = new Set(['ArrowUp', 'ArrowDown', 'ArrowLeft', 'ArrowRight', ' ', 'Shift']);

export class Controls {
  private readonly held = new Set<string>();
  private readonly codes = new Set<string>();
  /** The game's buttons by KeyboardEvent.code; empty: space and shift as always. */
  private buttons = new Map<string, number>();

  constructor(target: Window) {
    target.addEventListener('keydown', (e) => {
      if (this.buttons.has(e.code)) {
        this.codes.add(e.code);
        e.preventDefault();
        return;
      }
      if (!GAME_KEYS.has(e.key)) return;
      this.held.add(e.key);
      e.preventDefault(); // no scrolling on arrows and space
    });
    target.addEventListener('keyup', (e) => {
      this.held.delete(e.key);
      this.codes.delete(e.code);
    });
    // A key released while the window had no focus never sends keyup.
    target.addEventListener('blur', () => {
      this.held.clear();
      this.codes.clear();
    });
  }

  /** The game's declared inputs: each button on its key (a KeyboardEvent.code). */
  declare(inputs: { name: string; button: number; key: string }[]): void {
    this.buttons = new Map(inputs.filter((i) => i.button < 8 && i.key !== '').map((i) => [i.key, i.button]));
  }

  /** thrust and turn in [−1, 1] (turn positive = counter-clockwise, left), buttons. */
  read(): { thrust: number; turn: number; buttons: number } {
    const k = (key: string) => (this.held.has(key) ? 1 : 0);
    let buttons = 0;
    if (this.buttons.size > 0) for (const code of this.codes) buttons |= 1 << (this.buttons.get(code) ?? 0);
    else buttons = (k(' ') ? BUTTON_FIRE : 0) | (k('Shift') ? BUTTON_BOOST : 0);
    return { thrust: k('ArrowUp') - k('ArrowDown'), turn: k('ArrowLeft') - k('ArrowRight'), buttons };
  }
}
