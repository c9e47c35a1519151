// The keyboard as the game's controls: arrows turn and thrust, space fires, shift boosts.
// Input.buttons bits: 0 the world's impulse (the boost), 1 fire (server/world/input.hpp,
// games/asteroids/asteroids_rules.hpp).

export const BUTTON_BOOST = 1 << 0;
export const BUTTON_FIRE = 1 << 1;

const GAME_KEYS = new Set(['ArrowUp', 'ArrowDown', 'ArrowLeft', 'ArrowRight', ' ', 'Shift']);

export class Controls {
  private readonly held = new Set<string>();

  constructor(target: Window) {
    target.addEventListener('keydown', (e) => {
      if (!GAME_KEYS.has(e.key)) return;
      this.held.add(e.key);
      e.preventDefault(); // no scrolling on arrows and space
    });
    target.addEventListener('keyup', (e) => this.held.delete(e.key));
    // A key released while the window had no focus never sends keyup.
    target.addEventListener('blur', () => this.held.clear());
  }

  /** thrust and turn in [−1, 1] (turn positive = counter-clockwise, left), buttons. */
  read(): { thrust: number; turn: number; buttons: number } {
    const k = (key: string) => (this.held.has(key) ? 1 : 0);
    return {
      thrust: k('ArrowUp') - k('ArrowDown'),
      turn: k('ArrowLeft') - k('ArrowRight'),
      buttons: (k(' ') ? BUTTON_FIRE : 0) | (k('Shift') ? BUTTON_BOOST : 0),
    };
  }
}
