// The snapshot fan-out's side of a match: which clients are due this tick, the game's lines
// and events each one takes, the bodies' kinds and the bullets' shot origins.
#include "server/match/match.hpp"

#include <algorithm>

#include "protocol/config_hash.hpp"
#include "protocol/version.hpp"
#include "server/config/config_json.hpp"
#include "server/match/logger.hpp"
#include "server/match/shape_wire.hpp"

namespace arena::match {

using protocol::RejectCode;

void match::tag_new_bodies() {
    if (!rules_->has_state()) return;  // sandbox rules tag nothing
    // Ids only grow, and bodies are in id order: the new ones are the tail.
    const std::span<const world::body> bodies = world_.bodies();
    auto it = std::lower_bound(bodies.begin(), bodies.end(), kinds_asked_below_,
                               [](const world::body& b, uint32_t id) { return b.id < id; });
    for (; it != bodies.end(); ++it) {
        if (const uint8_t kind = rules_->kind_of(it->id); kind != 0) kinds_.set(it->id, kind);
        if (const rules::shot_record* shot = rules_->shot_of(it->id)) record_origin(it->id, *shot);
    }
    if (!bodies.empty()) kinds_asked_below_ = std::max(kinds_asked_below_, bodies.back().id + 1);
    retagged_.clear();
    rules_->take_retagged(retagged_);
    for (const uint32_t id : retagged_) kinds_.set(id, rules_->kind_of(id));
}

void match::record_origin(uint32_t body_id, const rules::shot_record& shot) {
    const auto p = players_.find(world::player_id{shot.shooter});
    if (p == players_.end()) return;
    const float values[] = {shot.position.x(), shot.position.y(), shot.velocity.x(), shot.velocity.y()};
    // A diverged world's NaN stays off the wire, as snapshot encoders keep it out of BodyState.
    for (const float v : values)
        if (!std::isfinite(v)) return;
    // The tick that fired it consumed this input: the bullet appeared in it.
    origins_.add(
        {body_id, shot.shooter, p->second.inputs.last_consumed_sequence(), values[0], values[1], values[2], values[3]});
}

void match::send_snapshots() {
    // BodyState clients all get theirs on the ticks that are multiples of the interval (one
    // shared frame when they see the whole world). Delta clients cost a view query and an
    // encoding each, so a big match spreads them over the interval in groups of player ids
    // (snapshot_group): a third of them on each tick at 60 Hz ticks and 20 Hz snapshots, not
    // all of them on one tick. A group's clients share their tick's work (one quantised state,
    // one prepared encoder per acknowledged tick, the bytes when their views are the same), so
    // a small match, one group, builds it once for all its players; matches start on
    // different ticks, which spreads a process of many small matches over the interval.
    const uint32_t interval = snapshot_interval();
    const uint32_t phase = world_.tick() % interval;
    // Player ids start at 1: players 1 to 16 are the first group.
    const auto group_phase = [&](world::player_id id) {
        return (id.value() - 1) / snapshot_group % interval;
    };
    kinds_.forget_missing(world_.bodies());
    origins_.forget_missing(world_.bodies());
    // The shared frame (BodyState clients of whole-world views, on the interval's ticks)
    // carries what changed since the previous one: its clients got that one.
    const bool shared_due = phase == 0 && fanout_.shared_full_frame() && !game_.empty();
    if (shared_due) shared_game_through_ = game_.collect(shared_game_sent_, shared_game_sent_, shared_game_);
    fanout_.begin(world_, &kinds_, shared_due ? &shared_game_ : nullptr, &origins_);
    // By id rather than by iterator: a send may end a connection, and with it a player.
    for (auto it = players_.begin(); it != players_.end();) {
        const world::player_id id = it->first;
        player& p = it->second;
        if (p.body_id && p.who && (p.snapshots.delta ? group_phase(id) : 0) == phase) {
            const size_t waiting = p.inputs.waiting();
            p.snapshots.extra_inputs_waiting =
                static_cast<uint16_t>(waiting > 1 ? std::min<size_t>(waiting - 1, 65535) : 0);
            send_snapshot(p, p.body_id, p.inputs.last_consumed_sequence());
        }
        it = players_.upper_bound(id);
    }
    // Spectators, BodyState clients all, on the interval's ticks, after the players.
    if (phase == 0) {
        for (auto it = spectators_.begin(); it != spectators_.end();) {
            const world::player_id id = it->first;
            send_snapshot(it->second, world::body_id{}, 0);  // no body: the whole world; no input to acknowledge
            it = spectators_.upper_bound(id);
        }
    }
    // The fan-out builds the shared frame only for a client that takes it.
    if (shared_due && fanout_.last_shared_tick() == world_.tick()) shared_game_sent_ = shared_game_through_;
}

template <class Reader>
const protocol::game_list* match::game_for(Reader& r, uint32_t& through) {
    if (game_.empty()) return nullptr;
    uint32_t held = 0;
    if (r.snapshots.delta) {
        held = r.snapshots.game_held();  // what its acknowledged snapshots brought
    } else {
        held = r.game_sent;  // a stream: what was sent arrived
    }
    // Within a datagram the game takes at most half: the bodies keep the rest.
    const size_t game_budget = r.snapshots.budget / 2;
    through = game_.collect(held, r.events_from, game_list_, game_budget);
    return &game_list_;
}

template <class Reader>
void match::send_snapshot(Reader& r, world::body_id own, uint32_t ack) {
    ++counters_.snapshots_sent;
    if (!r.snapshots.delta && fanout_.shared_full_frame()) {
        if (const protocol::snapshot_encoder* shared = fanout_.shared_frame(r.snapshots)) {
            counters_.snapshot_bytes = shared->frame().size();
            r.game_sent = shared_game_through_;
            if (outbox_) {
                outbox_->send_snapshot(*r.who, *shared, ack);
            } else {
                r.who->send_snapshot(*shared, ack);  // one memcpy, the ack patched in
            }
            return;
        }
    }
    uint32_t through = 0;
    const protocol::game_list* game = game_for(r, through);
    if (!r.snapshots.delta) r.game_sent = through;
    const auto frame = r.snapshots.delta ? fanout_.delta_frame(r.snapshots, own, ack, game)
                                         : fanout_.full_frame(r.snapshots, own, ack, game);
    if (r.snapshots.delta) r.snapshots.views.record_game(world_.tick(), through);
    counters_.snapshot_bytes = frame.size();
    if (outbox_) {
        outbox_->send_snapshot_frame(*r.who, frame);
    } else {
        r.who->send_snapshot_frame(frame);
    }
}

}  // namespace arena::match
