// Contact events, collision filters, and bodies added and removed between steps
// (server/world/contact_events.hpp, filter.hpp, world.hpp).
#include <catch2/catch.hpp>

#include "server/world/world.hpp"

using namespace arena::world;

namespace {

world_config space() {
    world_config c;
    c.air_density = 0;
    c.restitution_threshold = 1.0f;
    return c;
}

uint32_t add_ball(world& w, vec2 p, vec2 v, real restitution = 0.5f, collision_filter filter = {}) {
    body_material m;
    m.mass = 1;
    m.radius = 0.5f;
    m.restitution = restitution;
    m.friction = 0;
    body b = make_body(m, p);
    b.velocity = v;
    b.filter = filter;
    return *w.add_body(b);
}

}  // namespace

TEST_CASE("a head-on impact gives one event: ids, normal, approach speed and impulse in closed form",
          "[world][events]") {
    world w(space(), 1);
    w.set_contact_events(true);
    // 0.125 m apart, closing at 2 m/s (1/30 m a step): the gap is 0.025 m (beyond the 2 cm
    // speculative distance) at the fourth detection and −0.0083 m at the fifth.
    const uint32_t a = add_ball(w, {10, 10}, {1, 0});
    const uint32_t b = add_ball(w, {11.125f, 10}, {-1, 0});
    std::vector<std::pair<uint32_t, contact_event>> seen;
    for (int k = 0; k < 30; ++k) {
        w.step({});
        for (const contact_event& e : w.contact_events()) seen.push_back({w.tick(), e});
    }
    REQUIRE(seen.size() == 1);
    CHECK(seen[0].first == 5);
    const contact_event& e = seen[0].second;
    CHECK(e.a == a);
    CHECK(e.b == b);
    CHECK(e.normal.x() == Approx(1.0f));
    CHECK(e.normal.y() == Approx(0.0f).margin(1e-6));
    CHECK(e.approach_speed == Approx(2.0f));
    // Equal masses of 1 kg: effective mass 1/2, impulse (1 + e)·m_eff·v_rel = 1.5·0.5·2.
    CHECK(e.impulse == Approx(1.5f).epsilon(1e-5));
    CHECK(w.find(a)->velocity.x() == Approx(-0.5f).epsilon(1e-5));
}

TEST_CASE("pairs that begin touching in one step come out sorted by body ids", "[world][events]") {
    world w(space(), 1);
    w.set_contact_events(true);
    // Ids 1 and 2 far up the grid, 3 and 4 low: the broadphase meets 3–4 first.
    add_ball(w, {50, 150}, {1, 0});
    add_ball(w, {51.125f, 150}, {-1, 0});
    add_ball(w, {50, 5}, {1, 0});
    add_ball(w, {51.125f, 5}, {-1, 0});
    for (int k = 0; k < 5; ++k) w.step({});
    REQUIRE(w.contact_events().size() == 2);
    CHECK(w.contact_events()[0].a == 1);
    CHECK(w.contact_events()[0].b == 2);
    CHECK(w.contact_events()[1].a == 3);
    CHECK(w.contact_events()[1].b == 4);
}

TEST_CASE("contact events never change the state", "[world][events]") {
    world on(space(), 1), off(space(), 1);
    on.set_contact_events(true);
    for (world* w : {&on, &off}) {
        add_ball(*w, {10, 10}, {1, 0});
        add_ball(*w, {11.125f, 10}, {-1, 0});
    }
    for (int k = 0; k < 60; ++k) {
        on.step({});
        off.step({});
        REQUIRE(on.hash() == off.hash());
    }
    CHECK(off.contact_events().empty());
}

TEST_CASE("filters: bodies whose category is not in the other's mask pass through", "[world][filter]") {
    world w(space(), 1);
    w.set_contact_events(true);
    const uint32_t a = add_ball(w, {10, 10}, {1, 0}, 0.5f, {.category = 2, .mask = ~2u, .group = 0});
    const uint32_t b = add_ball(w, {11.125f, 10}, {-1, 0}, 0.5f, {.category = 2, .mask = ~0u, .group = 0});
    for (int k = 0; k < 120; ++k) {
        w.step({});
        REQUIRE(w.contact_events().empty());
    }
    // Unhindered: 2 s at 1 m/s each way.
    CHECK(w.find(a)->velocity.x() == 1.0f);
    CHECK(w.find(b)->velocity.x() == -1.0f);
    CHECK(w.find(a)->position.x() == Approx(12.0f).epsilon(1e-4));
}

TEST_CASE("filters: a negative group never collides, a positive one always does", "[world][filter]") {
    for (const int32_t group : {-3, 3}) {
        world w(space(), 1);
        w.set_contact_events(true);
        // Masks that would refuse the pair: only the group can make them collide.
        const collision_filter f{.category = 4, .mask = 0, .group = group};
        const uint32_t a = add_ball(w, {10, 10}, {1, 0}, 0.5f, f);
        add_ball(w, {11.125f, 10}, {-1, 0}, 0.5f, f);
        size_t events = 0;
        for (int k = 0; k < 30; ++k) {
            w.step({});
            events += w.contact_events().size();
        }
        CHECK(events == (group > 0 ? 1u : 0u));
        CHECK(w.find(a)->velocity.x() == (group > 0 ? Approx(-0.5f).epsilon(1e-5) : Approx(1.0f)));
    }
    CHECK(should_collide({}, {}));
    CHECK_FALSE(should_collide({.category = 1, .mask = 0, .group = 0}, {}));
}

TEST_CASE("a filter that is set is part of the hash, the default is not", "[world][filter]") {
    world plain(space(), 1), filtered(space(), 1);
    add_ball(plain, {10, 10}, {0, 0});
    add_ball(filtered, {10, 10}, {0, 0}, 0.5f, {.category = 1, .mask = ~0u, .group = 0});
    CHECK(plain.hash() == filtered.hash());
    filtered.find(1)->filter.mask = 1;
    CHECK(plain.hash() != filtered.hash());
}

TEST_CASE("bodies added and removed between steps: ids are never reused", "[world][spawn]") {
    world w(space(), 1);
    const uint32_t a = add_ball(w, {10, 10}, {0, 0});
    const uint32_t b = add_ball(w, {20, 10}, {0, 0});
    w.step({});
    REQUIRE(w.remove_body(b));
    const uint32_t c = add_ball(w, {30, 10}, {0, 0});
    CHECK(c == b + 1);
    const body_id removed[] = {body_id{a}, body_id{c}};
    w.remove_bodies(removed);
    w.step({});
    CHECK(add_ball(w, {40, 10}, {0, 0}) == c + 1);
    CHECK(w.bodies().size() == 1);
}

TEST_CASE("a pair that stays in contact reports once, apart and back again reports again", "[world][events]") {
    world w(space(), 1);
    w.set_contact_events(true);
    // Restitution 0, 1 m/s each way: they meet and rest against each other.
    add_ball(w, {10, 10}, {1, 0}, 0);
    add_ball(w, {11.125f, 10}, {-1, 0}, 0);
    size_t events = 0;
    for (int k = 0; k < 60; ++k) {
        w.step({});
        events += w.contact_events().size();
    }
    CHECK(events == 1);
    // Pulled apart by hand and pushed together again: a new touch.
    w.find(1)->velocity = {-1, 0};
    w.find(2)->velocity = {1, 0};
    for (int k = 0; k < 30; ++k) w.step({});
    w.find(1)->velocity = {1, 0};
    w.find(2)->velocity = {-1, 0};
    for (int k = 0; k < 60; ++k) {
        w.step({});
        events += w.contact_events().size();
    }
    CHECK(events == 2);
}
