#pragma once
// What an interpolating client shows of the others (as the page does): the world a fixed delay
// behind its own predicted present, between the two snapshots around that moment. The delay is
// the largest lag of a snapshot behind the present over the last second, plus one snapshot
// interval, so that the moment shown almost always lies between two snapshots already in hand
// and moves smoothly, a tick per tick. A body that came or went between two snapshots is shown
// while the server's events say it was there (a rock hit goes at the event's tick, and its
// fragments come then). Its inputs carry that moment (Input.view_tick and
// view_fraction: lag compensation), and its hits are judged against it
// (hit_registration.hpp): a bullet fired with the view `rewind` behind is seen, for its whole
// flight, against the others that far behind, as the server judges it.
#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <span>
#include <vector>

#include "protocol/messages.hpp"
#include "server/world/config.hpp"
#include "server/world/types.hpp"

namespace arena::bots {

class shown_view {
public:
    // `interval`: ticks between two snapshots.
    explicit shown_view(std::uint32_t interval = 3) : interval_(interval) {}
    void set_interval(std::uint32_t interval) { interval_ = interval; }

    // The snapshot of `tick` arrived while the client's own present was `predicted`.
    void on_snapshot(std::uint32_t tick, std::uint32_t predicted, std::span<const protocol::BodyState> bodies);

    // How far behind its present the client shows the others, 1/256 ticks (0 before a snapshot).
    [[nodiscard]] std::uint32_t delay() const { return delay_; }
    // The moment shown while the present is `predicted`, 1/256 ticks (0 before a snapshot).
    [[nodiscard]] std::uint64_t moment(std::uint32_t predicted) const;

    struct shown_body {
        std::uint32_t id = 0;
        world::vec2 position{0, 0};
    };
    // The server's word on when a body went (a rock hit, a ship destroyed: the event's tick, the
    // first whose state lacks it) or came (a respawned ship's), for the views between which it
    // did.
    void went(std::uint32_t body, std::uint32_t tick);
    void came(std::uint32_t body, std::uint32_t tick);

    // Every body shown at `moment`: between its places in the two kept snapshots around the
    // moment; a body of only one of them while it was there (went() and came() say when; a
    // newcomer without a word came with the last body that went between the two, else with
    // the newer; one that went without a word is not shown), carried by its velocity from the
    // snapshot that has it; past the newest snapshot (or before the oldest), that one's bodies
    // carried on (or back) by their velocity.
    [[nodiscard]] std::vector<shown_body> at(std::uint64_t moment, const world::world_config& config) const;

private:
    struct kept {
        std::uint32_t tick = 0;
        std::vector<protocol::BodyState> bodies;  // by increasing id
    };
    static constexpr std::size_t kept_views = 16;  // 0.8 s at 20 Hz: more than the 250 ms cap
    static constexpr std::size_t kept_lags = 20;   // a second of snapshots at 20 Hz

    std::uint32_t interval_;
    std::deque<kept> views_;  // oldest first
    std::deque<std::uint32_t> lags_;
    std::map<std::uint32_t, std::uint32_t> went_;  // body id → the tick it went
    std::map<std::uint32_t, std::uint32_t> came_;  // body id → the tick it came
    std::uint32_t delay_ = 0;
};

}  // namespace arena::bots
