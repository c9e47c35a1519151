// Playing the page as a person would, for the browser tests and bench/page_hits.mjs: turn
// towards the nearest target as the page draws it, with the arrow keys, and hold fire.

// The bearing from the own ship's facing to the nearest drawn body of one of `kinds` (not the
// player's own, not predicted), radians in [−π, π]; null when there is none or no own ship.
function bearingToNearest(page, kinds) {
  return page.evaluate((wanted) => {
    const { client, playerId } = window.arenaPage;
    const state = client.stateAt(performance.now());
    const own = state.own;
    if (!own) return null;
    const { width, height } = client.session.world;
    let best = null;
    for (const b of state.bodies) {
      if (b.predicted || !wanted.includes(b.kind) || b.owner === playerId) continue;
      const dx = b.x - own.x - Math.round((b.x - own.x) / width) * width;
      const dy = b.y - own.y - Math.round((b.y - own.y) / height) * height;
      const d = Math.hypot(dx, dy);
      if (!best || d < best.d) best = { d, bearing: Math.atan2(dy, dx) };
    }
    if (!best) return null;
    const diff = best.bearing - own.angle;
    return Math.atan2(Math.sin(diff), Math.cos(diff));
  }, kinds);
}

// Holds the space bar and steers at the nearest body of `kinds` (Asteroids: rock 2, ship 1)
// until `done()` is truthy or `ms` pass; releases every key it pressed.
export async function fireAtNearest(page, kinds, ms, done = async () => false) {
  const sleep = (t) => new Promise((r) => setTimeout(r, t));
  await page.keyboard.down(' ');
  let held = null;
  for (const end = Date.now() + ms; Date.now() < end && !(await done());) {
    const diff = await bearingToNearest(page, kinds);
    const want = diff === null || Math.abs(diff) < 0.05 ? null : diff > 0 ? 'ArrowLeft' : 'ArrowRight';
    if (want !== held) {
      if (held) await page.keyboard.up(held);
      if (want) await page.keyboard.down(want);
      held = want;
    }
    await sleep(30);
  }
  if (held) await page.keyboard.up(held);
  await page.keyboard.up(' ');
}
