// The prediction of own shots (client_sim/own_shots.hpp) against a local "server": a world
// played by the Asteroids rules and fed the same inputs. With no loss the predicted ship
// stays bit-exact while firing (the recoil), and every predicted shot matches the server's
// exactly; a server that fires where the client did not, or not where it did, is counted.
#include <catch2/catch.hpp>
#include <cstring>
#include <deque>

#include "client_sim/behavior.hpp"
#include "client_sim/prediction.hpp"
#include "games/asteroids/asteroids_rules.hpp"
#include "server/world/presets.hpp"
#include "server/world/world.hpp"

namespace {

using arena::bots::behavior;
using arena::bots::behavior_kind;
using arena::bots::predictor;
using arena::protocol::BodyState;
using arena::protocol::ShotOrigin;
namespace world = arena::world;
namespace rules = arena::rules;

constexpr std::uint32_t player = 2;

// The asteroids preset played by the Asteroids rules, without the preset's rocks (the rules
// bring a wave of one far from the ship).
world::world_config asteroids_game() {
    world::world_config c = *world::preset_by_name("asteroids");
    c.rocks.count = 0;
    c.rules = "asteroids";
    return c;
}

BodyState state_of(const world::body& b) {
    return BodyState(b.id, b.owner, b.position.x(), b.position.y(), b.velocity.x(), b.velocity.y(), b.angle,
                     b.angular_velocity);
}

// The server's side: the world and its rules, one player, and the origins of the bullets
// that appeared since the last snapshot, tagged with the input that fired them (as
// server/match/ does).
struct server_game {
    world::world w;
    rules::asteroids_rules r;
    std::uint32_t ship = 0;
    std::uint32_t seen_below = 0;  // bodies below this id were looked at for origins
    std::vector<ShotOrigin> origins;

    explicit server_game(const world::world_config& c) : w(c, 3), r(w) {
        const world::player_id owners[] = {world::player_id{player}};
        ship = w.spawn_players(owners)[0].value();
        const std::uint32_t bodies[] = {ship};
        const std::uint32_t ids[] = {player};
        r.on_joins(w, ids, bodies);
        seen_below = ship + 1;
    }
    void step(std::uint32_t sequence, const world::player_input& in) {
        const world::tick_inputs inputs{{world::body_id{ship}, in}};
        r.before_step(w, inputs);
        w.step(inputs);
        r.after_step(w);
        for (const world::body& b : w.bodies()) {
            if (b.id < seen_below) continue;
            if (const rules::shot_record* s = r.shot_of(b.id))
                origins.emplace_back(b.id, s->shooter, sequence, s->position.x(), s->position.y(), s->velocity.x(),
                                     s->velocity.y());
        }
        if (!w.bodies().empty()) seen_below = w.bodies().back().id + 1;
    }
    std::vector<BodyState> view() const {
        std::vector<BodyState> out;
        for (const world::body& b : w.bodies()) out.push_back(state_of(b));
        return out;
    }
};

bool same_bits(float a, float b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

bool same_body(const world::body& a, const world::body& b) {
    return same_bits(a.position.x(), b.position.x()) && same_bits(a.position.y(), b.position.y()) &&
           same_bits(a.velocity.x(), b.velocity.x()) && same_bits(a.velocity.y(), b.velocity.y()) &&
           same_bits(a.angle, b.angle) && same_bits(a.angular_velocity, b.angular_velocity);
}

// Snapshots on their way to the client: the server's state after a tick (the own ship, the
// view and the origins of the bullets that appeared since the last one), each arriving at a
// chosen tick of the client's.
class snapshot_wire {
public:
    // A snapshot of `server` now, acknowledging input `ack`, arriving at tick `arrives`.
    void send(std::uint32_t arrives, server_game& server, std::uint32_t ack) {
        in_flight_.push_back({arrives, server.w.tick(), ack, state_of(*server.w.find(server.ship)), server.view(),
                              std::move(server.origins)});
        server.origins.clear();
    }
    // Hands `p` every snapshot that arrived by tick `now`.
    void deliver(std::uint32_t now, predictor& p) {
        while (!in_flight_.empty() && in_flight_.front().arrives <= now) {
            const in_flight& f = in_flight_.front();
            REQUIRE(p.on_snapshot(f.tick, f.ack, &f.own, f.view, f.origins).problem == predictor::ack_problem::none);
            in_flight_.pop_front();
        }
    }

private:
    struct in_flight {
        std::uint32_t arrives;
        std::uint32_t tick;
        std::uint32_t ack;
        BodyState own;
        std::vector<BodyState> view;
        std::vector<ShotOrigin> origins;
    };
    std::deque<in_flight> in_flight_;
};

// A random walk that holds fire on most ticks: the cooldown and the cap decide the shots.
world::player_input firing(behavior& drive, const predictor& p, std::uint32_t sequence) {
    world::player_input in = drive.next({p.body()});
    if (sequence % 50 < 40) in.buttons = static_cast<std::uint8_t>(in.buttons | rules::button_fire);
    return in;
}

}  // namespace

TEST_CASE("with no loss the predicted ship is bit-exact while firing, and every shot spawns exactly",
          "[bots][prediction][shots]") {
    const std::uint32_t interval = GENERATE(1u, 3u);  // ticks between snapshots
    const std::uint32_t delay = GENERATE(0u, 4u);     // ticks between a snapshot and its arrival
    server_game server(asteroids_game());
    predictor p(server.w.config(), server.ship, player);
    behavior drive(behavior_kind::random, 5, 1, server.w.config());

    snapshot_wire wire;
    wire.send(0, server, 0);
    for (std::uint32_t t = 0; t <= 900; ++t) {
        wire.deliver(t, p);
        const std::uint32_t s = t + 1;
        const world::player_input in = firing(drive, p, s);
        p.on_input(s, in);
        server.step(s, in);
        const world::body* ship = server.w.find(server.ship);
        REQUIRE(ship != nullptr);  // nothing may hit it: the test is about a lone ship
        if (p.body() != nullptr) REQUIRE(same_body(*p.body(), *ship));  // the recoil included
        if (s % interval == 0) wire.send(s + delay, server, s);
    }
    const arena::bots::shot_counts& counts = p.shots().counts();
    const std::uint32_t fired = server.r.scoreboard()[0].shots;
    CHECK(fired > 40);
    // The shots still in flight or waiting at the end aside, each one matched exactly.
    CHECK(counts.exact + p.shots().waiting().size() >= fired - 2);
    CHECK(counts.exact > 40);
    CHECK(counts.with_error == 0);
    CHECK(counts.unconfirmed == 0);
    CHECK(counts.unpredicted == 0);
    CHECK(p.take_shot_errors().empty());
}

TEST_CASE("a shot the server did not fire is unconfirmed, one it fired unpredicted, one that differs has an error",
          "[bots][prediction][shots]") {
    server_game server(asteroids_game());
    predictor p(server.w.config(), server.ship, player);
    const BodyState start = state_of(*server.w.find(server.ship));
    REQUIRE(p.on_snapshot(server.w.tick(), 0, &start, server.view()).own_found);
    const world::player_input fire{0, 0, rules::button_fire};
    // Input 1 fires on both sides, but the server's spawn is moved by 1 cm.
    p.on_input(1, fire);
    server.step(1, fire);
    REQUIRE(server.origins.size() == 1);
    const ShotOrigin o = server.origins[0];
    server.origins[0] = ShotOrigin(o.body_id(), o.owner(), o.input_sequence(), o.x() + 0.01f, o.y(), o.vx(), o.vy());
    // Input 2 holds fire too, but within the cooldown: no second shot.
    p.on_input(2, fire);
    REQUIRE(p.shots().waiting().size() == 1);
    auto snapshot = [&](std::uint32_t ack) {
        const BodyState own = state_of(*server.w.find(server.ship));
        const std::vector<BodyState> view = server.view();
        const auto c = p.on_snapshot(server.w.tick(), ack, &own, view, server.origins);
        server.origins.clear();
        return c;
    };
    snapshot(1);
    CHECK(p.shots().counts().with_error == 1);
    const std::vector<float> errors = p.take_shot_errors();
    REQUIRE(errors.size() == 1);
    CHECK(errors[0] == Approx(0.01f).margin(1e-4));
    // Past the cooldown the client fires on input 8, which the server never gets (it steps a
    // silent input instead), and the server fires on input 9, which the client sent silent.
    for (std::uint32_t s = 2; s <= 8; ++s) server.step(s, {});
    for (std::uint32_t s = 3; s <= 8; ++s) p.on_input(s, s == 8 ? fire : world::player_input{});
    REQUIRE(p.shots().waiting().size() == 1);
    p.on_input(9, {});
    server.step(9, fire);
    snapshot(9);
    CHECK(p.shots().counts().unconfirmed == 1);
    CHECK(p.shots().counts().unpredicted == 1);
    CHECK(p.shots().waiting().empty());
}

TEST_CASE("after late inputs the server repeated a tick for, the gun still counts in the server's ticks",
          "[bots][prediction][shots]") {
    // Every 40th tick the client's input is late: the server steps its last one again (an
    // underrun) and takes each later input a tick later than before. Bullets expire and the
    // cooldown ends in the server's ticks; a client that counted them in its own inputs would
    // fire a tick early after each late input, for as long as the bullets fired before it live.
    server_game server(asteroids_game());
    predictor p(server.w.config(), server.ship, player);
    behavior drive(behavior_kind::random, 5, 1, server.w.config());
    snapshot_wire wire;
    wire.send(0, server, 0);
    std::deque<std::pair<std::uint32_t, world::player_input>> waiting;  // sent, not yet taken
    std::pair<std::uint32_t, world::player_input> last{0, {}};
    std::uint32_t underruns = 0;
    for (std::uint32_t t = 0; t <= 1800; ++t) {
        wire.deliver(t, p);
        const std::uint32_t s = t + 1;
        const world::player_input in = firing(drive, p, s);
        p.on_input(s, in);
        waiting.emplace_back(s, in);
        if (t % 40 == 39) {
            ++underruns;  // this tick's input is late: the last one again
        } else {
            last = waiting.front();
            waiting.pop_front();
        }
        server.step(last.first, last.second);
        REQUIRE(server.w.find(server.ship) != nullptr);
        if (server.w.tick() % 3 == 0) wire.send(t + 4, server, last.first);
    }
    const arena::bots::shot_counts& counts = p.shots().counts();
    const std::uint32_t fired = server.r.scoreboard()[0].shots;
    REQUIRE(underruns == 45);
    CHECK(fired > 80);
    CHECK(counts.exact + counts.with_error > 80);
    // What is left: a repeated input holds fire too, and now and then the server's gun is
    // ready in the repeated tick, so it fires a shot the client could not foresee and refuses
    // the client's next one (measured 5 and 7 here; counted in inputs, 6 and 38, and only 58
    // shots matched).
    INFO("unconfirmed " << counts.unconfirmed << ", unpredicted " << counts.unpredicted << " of " << fired);
    CHECK(counts.unconfirmed + counts.unpredicted <= underruns / 3);
}
