// Recordings changed on purpose, for the tests of the replay player and the replay page.

// FNV-1a 32, the record check (server/replay/README.md).
function fnv1a(bytes) {
  let h = 0x811c9dc5;
  for (const b of bytes) h = Math.imul(h ^ b, 0x01000193) >>> 0;
  return h;
}

// The recording with the first recorded Hash after the start changed (its checksum made right
// again, so that the reader lets it through): the tick and the hash it held. `hashes`: the
// world's {tick, hash} at every tick, as arena-replay --dump-hashes has them.
export function withChangedHash(bytes, hashes) {
  const tickOf = new Map(hashes.slice(1).map((h) => [h.hash, h.tick]));
  const out = bytes.slice();
  const d = new DataView(out.buffer);
  for (let at = 0; at + 4 <= out.length; ) {
    const length = d.getUint32(at, true);
    const body = out.subarray(at + 4, at + 4 + length);
    for (let i = 0; length < 64 && i + 8 <= body.length; ++i) {
      const hex = [...body.subarray(i, i + 8)].reverse().map((b) => b.toString(16).padStart(2, '0')).join('');
      if (!tickOf.has(hex)) continue;
      body[i] ^= 0x01;
      d.setUint32(at + 4 + length, fnv1a(body), true);
      return { bytes: out, tick: tickOf.get(hex), recorded: hex };
    }
    at += 4 + length + 4;
  }
  throw new Error('no Hash record found');
}
