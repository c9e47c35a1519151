#pragma once
// Hit registration (docs/LAG_COMPENSATION.md, "Hit registration, measured"): how often the server
// confirms a hit its shooter saw. A *claim* is a hit the client saw: one of its own bullets, where
// its prediction has it (session::own_bullets), swept over the tick against a target's circle in
// the view it shows (the newest snapshot's bodies, the view moment its inputs carry). One claim
// per bullet. The server's verdict is its game events: a hit by this player on a target. A claim
// is *confirmed* by a server hit on the same target within `window` ticks of it; a server hit
// with no claim on that target within the window is *unclaimed*. Each server hit confirms at most
// one claim and each claim is confirmed by at most one hit.
//
// Ticks: a claim's is the tick of the view it was seen in, a hit's the server's tick of the
// event; the hit comes about a round trip (and the rewind) after the view, well within a window
// of a second.
#include <cstdint>
#include <vector>

namespace arena::bots {

struct hit_counts {
    std::uint64_t claimed = 0;         // hits the client saw (one per bullet)
    std::uint64_t confirmed = 0;       // of those, hit on the server within the window
    std::uint64_t unclaimed_hits = 0;  // server hits by this player the client never saw
    // Claims never confirmed whose target something else took within the window (another
    // player's bullet, or for a ship a rock): the server judges only targets still there.
    std::uint64_t contested = 0;
};

class hit_registration {
public:
    // `window`: ticks between a claim and the server's hit on the same target (1 s of ticks).
    explicit hit_registration(std::uint32_t window = 60) : window_(window) {}
    void set_window(std::uint32_t window) { window_ = window; }

    // The bullet fired by input `sequence` met `target` in the view of `tick`. Only its first
    // claim counts; later ones of the same bullet are ignored. The target is then gone as this
    // client sees it (a hit rock splits into new bodies, a hit ship is destroyed): no other
    // bullet claims it.
    void claim(std::uint32_t sequence, std::uint32_t target, std::uint32_t tick);
    // True when the bullet fired by input `sequence` has claimed a hit.
    [[nodiscard]] bool has_claimed(std::uint32_t sequence) const;
    // True when a bullet of this player claimed `target`.
    [[nodiscard]] bool taken(std::uint32_t target) const;
    // The server's event: this player's bullet hit `target` in `tick`.
    void server_hit(std::uint32_t target, std::uint32_t tick);
    // The server's event: `target` was hit or destroyed in `tick` by something other than this
    // player's bullets.
    void other_hit(std::uint32_t target, std::uint32_t tick);
    // The newest view is of `tick`: claims and hits whose window closed are settled.
    void advance(std::uint32_t tick);
    // The run is over at view `tick`: claims whose window is still open are left out (no
    // verdict could come in time), server hits still unmatched are unclaimed.
    void finish(std::uint32_t tick);

    [[nodiscard]] const hit_counts& counts() const { return counts_; }

private:
    struct pending {
        std::uint32_t target = 0;
        std::uint32_t tick = 0;
    };
    // A claim meets a waiting server hit, or a server hit a waiting claim, of `target` within the
    // window: the oldest such is taken out of `waiting` and counted confirmed.
    bool settle(std::vector<pending>& waiting, std::uint32_t target, std::uint32_t tick);

    std::uint32_t window_;
    std::vector<pending> claims_;                   // not confirmed yet, oldest first
    std::vector<pending> hits_;                     // server hits not matched yet, oldest first
    std::vector<pending> others_;                   // others' hits of the last two windows, oldest first
    std::vector<std::uint32_t> claimed_sequences_;  // bullets that claimed, while they may fly
    std::vector<std::uint32_t> taken_;              // targets claimed, the newest few
    hit_counts counts_;
};

}  // namespace arena::bots
