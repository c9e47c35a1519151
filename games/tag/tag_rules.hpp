#pragma once
// Tag, the tutorial's game (docs/GAMES.md): one player is "it"; touching another passes it on
// (no tag-back for a second); whoever spends the least time as "it" wins.
#include <map>

#include "server/rules/rules.hpp"

namespace arena::rules {

class tag_rules : public rules {
public:
    explicit tag_rules(world::world& w);

    void on_joins(world::world& w, std::span<const uint32_t> owners, std::span<const uint32_t> bodies) override;
    void on_leaves(world::world& w, std::span<const uint32_t> bodies) override;
    void after_step(world::world& w) override;

    uint8_t kind_of(uint32_t body_id) const override;
    void take_retagged(std::vector<uint32_t>& into) override;
    bool has_state() const override { return true; }
    void hash(world::fnv1a& h) const override;
    std::vector<score_line> scoreboard() const override;
    std::vector<uint32_t> winners() const override;
    protocol::game_manifest manifest() const override;
    std::span<const declared_event> declared_events() const override { return events_; }

    uint32_t it() const { return it_; }
    uint32_t ticks_it(uint32_t player) const { return players_.at(player).ticks_it; }

private:
    struct player {
        uint32_t body = 0;
        uint32_t ticks_it = 0;  // world ticks spent as "it"
    };
    void make_it(uint32_t player, uint32_t tick);

    std::map<uint32_t, player> players_;  // by player id
    uint32_t it_ = 0;                     // the player who is "it", 0 = nobody yet
    uint32_t immune_until_ = 0;           // no tag-back before this world tick
    std::vector<declared_event> events_;  // the last after_step's
    std::vector<uint32_t> retagged_;      // bodies whose tag changed since take_retagged
};

}  // namespace arena::rules
