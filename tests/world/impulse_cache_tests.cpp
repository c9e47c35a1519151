// The warm-start cache (contacts.hpp): a contact finds the impulses its body pair and features
// had last step, whatever the order the contacts come in this step; anything new starts at zero.
#include <catch2/catch.hpp>
#include <vector>

#include "server/world/contacts.hpp"

using namespace arena::world;

namespace {

std::vector<body> bodies_with_ids(uint32_t n) {
    std::vector<body> bodies(n);
    for (uint32_t i = 0; i < n; ++i) bodies[i].id = 100 + 7 * i;
    return bodies;
}

contact between(uint32_t a, uint32_t b, uint16_t first_id, real normal, real tangent) {
    contact c;
    c.a = a;
    c.b = b;
    c.count = 2;
    c.points[0].id = first_id;
    c.points[1].id = static_cast<uint16_t>(first_id + 1);
    c.points[0].normal_impulse = normal;
    c.points[0].tangent_impulse = tangent;
    c.points[1].normal_impulse = 2 * normal;
    c.points[1].tangent_impulse = 2 * tangent;
    return c;
}

contact on_floor(uint32_t a, real normal) {
    contact c = between(a, a, 0, normal, 0);
    c.with = wall::bottom;
    return c;
}

// A contact as detection makes it: no impulses yet.
contact fresh(contact c) {
    for (contact_point& p : c.points) p.normal_impulse = p.tangent_impulse = 0;
    return c;
}

}  // namespace

TEST_CASE("the warm-start cache gives each contact its own impulses, in any order", "[world][contacts]") {
    const std::vector<body> bodies = bodies_with_ids(8);
    impulse_cache cache;
    std::vector<contact> last;
    for (uint32_t i = 0; i + 1 < 8; ++i) last.push_back(between(i, i + 1, 4, 1.0f + i, 0.5f + i));
    last.push_back(on_floor(0, 9.0f));
    cache.store(bodies, last);

    SECTION("the same order (the walk)") {
        std::vector<contact> now;
        for (const contact& c : last) now.push_back(fresh(c));
        cache.load(bodies, now);
        for (size_t i = 0; i < now.size(); ++i) {
            INFO("contact " << i);
            CHECK(now[i].points[0].normal_impulse == last[i].points[0].normal_impulse);
            CHECK(now[i].points[1].tangent_impulse == last[i].points[1].tangent_impulse);
        }
    }
    SECTION("reversed, one gone, one new, a feature changed (the table)") {
        std::vector<contact> now;
        now.push_back(fresh(between(2, 6, 4, 0, 0)));                          // a pair that did not touch last step
        for (size_t i = last.size(); i-- > 1;) now.push_back(fresh(last[i]));  // contact 0 is gone
        now[3].points[1].id = 9;                                               // another feature of the same pair
        cache.load(bodies, now);
        CHECK(now[0].points[0].normal_impulse == 0);
        CHECK(now[0].points[1].normal_impulse == 0);
        CHECK(now[1].with == wall::bottom);
        CHECK(now[1].points[0].normal_impulse == 9.0f);
        for (size_t k = 2; k < now.size(); ++k) {
            const contact& before = last[last.size() - k];
            INFO("contact " << k);
            CHECK(now[k].points[0].normal_impulse == before.points[0].normal_impulse);
            CHECK(now[k].points[0].tangent_impulse == before.points[0].tangent_impulse);
            if (k == 3) {
                CHECK(now[k].points[1].normal_impulse == 0);
            } else {
                CHECK(now[k].points[1].normal_impulse == before.points[1].normal_impulse);
            }
        }
    }
    SECTION("bodies keep their pair's impulses when their indices move") {
        // The key is the bodies' ids: the same two bodies at other indices are the same pair.
        std::vector<body> moved = bodies;
        std::swap(moved[0], moved[7]);
        std::vector<contact> now{fresh(between(7, 1, 4, 0, 0))};
        cache.load(moved, now);
        CHECK(now[0].points[0].normal_impulse == last[0].points[0].normal_impulse);
        CHECK(now[0].points[1].tangent_impulse == last[0].points[1].tangent_impulse);
    }
    SECTION("a step without contacts forgets them") {
        cache.store(bodies, {});
        std::vector<contact> now{fresh(last[2])};
        cache.load(bodies, now);
        CHECK(now[0].points[0].normal_impulse == 0);
    }
}
