// Shapes reach clients (protocol/README.md, "Shapes"): which bodies a snapshot describes
// (shape_tracker.hpp), the static geometry of the Welcome, and a Welcome that always fits the
// frame limit. The lossy end-to-end session is in snapshot_fanout_tests.cpp.
#include <catch2/catch.hpp>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "match/drive.hpp"
#include "protocol/decode.hpp"
#include "protocol/verify.hpp"
#include "protocol/version.hpp"
#include "server/config/config_json.hpp"
#include "server/match/match.hpp"
#include "server/match/shape_tracker.hpp"
#include "server/match/shape_wire.hpp"
#include "server/world/presets.hpp"

using namespace arena;

namespace {

std::vector<world::body> bodies_with_ids(std::initializer_list<uint32_t> ids,
                                         std::initializer_list<uint32_t> static_ids = {}) {
    std::vector<world::body> out;
    for (const uint32_t id : ids) {
        world::body b;
        b.id = id;
        if (std::find(static_ids.begin(), static_ids.end(), id) != static_ids.end()) b.inv_mass = 0;
        out.push_back(b);
    }
    return out;
}

// The ids one update describes, with the bodies' kinds in `kinds`.
std::vector<uint32_t> described(match::shape_tracker& t, uint32_t tick, const std::vector<world::body>& bodies,
                                std::vector<uint32_t> view, uint32_t acked, bool reliable = false,
                                const match::body_kinds& kinds = {}) {
    std::vector<uint32_t> ids;
    t.update(tick, bodies, view, acked, reliable, kinds, [&](uint32_t i) { ids.push_back(bodies[i].id); });
    return ids;
}

using ids = std::vector<uint32_t>;

}  // namespace

TEST_CASE("a shape is described in every snapshot until one that carried it is acknowledged", "[match][shapes]") {
    const auto bodies = bodies_with_ids({4, 7, 9});
    match::shape_tracker t;
    t.welcomed(1);
    CHECK(described(t, 3, bodies, {0, 1}, 0) == ids{4, 7});
    CHECK(described(t, 6, bodies, {0, 1}, 0) == ids{4, 7});  // 3 lost, or its ack late
    CHECK(described(t, 9, bodies, {0, 1, 2}, 3) == ids{9});  // 3 arrived: 4 and 7 are held
    CHECK(t.known() == 2);
    CHECK(t.pending() == 1);
    // 7 leaves the view (the client forgets it), then comes back at 15.
    CHECK(described(t, 12, bodies, {0, 2}, 6) == ids{9});  // 6 carried no 9 yet
    CHECK(described(t, 15, bodies, {0, 1, 2}, 9) == ids{7});
    // A late ack of a snapshot before 7 came back does not make it held: the client dropped it
    // at 12.
    CHECK(described(t, 18, bodies, {0, 1, 2}, 12) == ids{7});
    CHECK(described(t, 21, bodies, {0, 1, 2}, 15).empty());
    CHECK(t.known() == 3);
    CHECK(t.pending() == 0);
}

TEST_CASE("a body whose kind changes is described again until a snapshot with its new kind is acknowledged",
          "[match][shapes]") {
    const auto bodies = bodies_with_ids({4, 7, 9});
    match::body_kinds kinds;
    kinds.set(7, 1);
    match::shape_tracker t;
    t.welcomed(1);
    CHECK(described(t, 3, bodies, {0, 1, 2}, 0, false, kinds) == ids{4, 7, 9});
    CHECK(described(t, 6, bodies, {0, 1, 2}, 3, false, kinds).empty());  // all held
    kinds.set(7, 2);                                                     // "it" changes hands
    kinds.set(9, 2);
    CHECK(described(t, 9, bodies, {0, 1, 2}, 6, false, kinds) == ids{7, 9});
    kinds.set(9, 0);  // and again before the client had the first change: 9 from its new start
    CHECK(described(t, 12, bodies, {0, 1, 2}, 6, false, kinds) == ids{7, 9});
    CHECK(described(t, 15, bodies, {0, 1, 2}, 9, false, kinds) == ids{9});  // 9 carried 7's new kind
    CHECK(described(t, 18, bodies, {0, 1, 2}, 12, false, kinds).empty());
    CHECK(t.known() == 3);
    kinds.set(4, 3);  // an unchanged kind costs nothing; a changed one counts
    const uint64_t revision = kinds.revision();
    kinds.set(4, 3);
    CHECK(kinds.revision() == revision);
    // A reliable stream holds the new kind once it is sent.
    match::shape_tracker r;
    r.welcomed(1);
    CHECK(described(r, 3, bodies, {0, 1, 2}, 0, true, kinds) == ids{4, 7, 9});
    kinds.set(4, 1);
    CHECK(described(r, 6, bodies, {0, 1, 2}, 0, true, kinds) == ids{4});
    CHECK(described(r, 9, bodies, {0, 1, 2}, 0, true, kinds).empty());
}

TEST_CASE("a reliable stream describes each shape once per stay in the view", "[match][shapes]") {
    const auto bodies = bodies_with_ids({4, 7, 9});
    match::shape_tracker t;
    t.welcomed(1);
    CHECK(described(t, 3, bodies, {0, 1, 2}, 0, true) == ids{4, 7, 9});
    CHECK(described(t, 6, bodies, {0, 1, 2}, 0, true).empty());
    CHECK(described(t, 9, bodies, {0, 2}, 0, true).empty());
    CHECK(described(t, 12, bodies, {0, 1, 2}, 0, true) == ids{7});
}

TEST_CASE("an unchanged view of held shapes describes nothing, a new body at the same index is described",
          "[match][shapes]") {
    match::shape_tracker t;
    t.welcomed(1);
    const auto bodies = bodies_with_ids({4, 7, 9});
    CHECK(described(t, 3, bodies, {0, 1, 2}, 0, true) == ids{4, 7, 9});
    CHECK(described(t, 6, bodies, {0, 1, 2}, 0, true).empty());
    CHECK(described(t, 9, bodies, {0, 1, 2}, 0, true).empty());
    // 9 removed and 12 spawned: the same count and the same indices, another body.
    const auto replaced = bodies_with_ids({4, 7, 12});
    CHECK(described(t, 12, replaced, {0, 1, 2}, 0, true) == ids{12});
    // 4 removed: the same view's indices now name other bodies, all held.
    const auto fewer = bodies_with_ids({7, 12});
    CHECK(described(t, 15, fewer, {0, 1}, 0, true).empty());
    CHECK(t.known() == 2);
    // Over a lossy link the shortcut waits until every description was acknowledged.
    match::shape_tracker lossy;
    lossy.welcomed(1);
    CHECK(described(lossy, 3, bodies, {0, 1, 2}, 0) == ids{4, 7, 9});
    CHECK(described(lossy, 6, bodies, {0, 1, 2}, 0) == ids{4, 7, 9});
    CHECK(described(lossy, 9, bodies, {0, 1, 2}, 3).empty());
    CHECK(described(lossy, 12, bodies, {0, 1, 2}, 3).empty());
    CHECK(lossy.pending() == 0);
}

TEST_CASE("static bodies the Welcome carried are never described, later ones are", "[match][shapes]") {
    const auto early = bodies_with_ids({2, 5}, {2});
    match::shape_tracker t;
    t.welcomed(6);  // the Welcome covered ids below 6
    CHECK(described(t, 3, early, {0, 1}, 0) == ids{5});
    const auto later = bodies_with_ids({2, 5, 8}, {2, 8});
    CHECK(described(t, 6, later, {0, 1, 2}, 3) == ids{8});
}

TEST_CASE("the Welcome carries every static body with its pose, shape and kind", "[match][shapes]") {
    match::match g({}, world::platformer_preset());
    size_t statics = 0;
    for (const world::body& b : g.state().bodies()) {
        if (!b.is_static()) continue;
        ++statics;
        g.set_body_kind(b.id, 7);
    }
    REQUIRE(statics > 0);
    const protocol::welcome_info w = g.welcome_for(1, 1);
    const auto back = protocol::decode_welcome(
        *protocol::verify_message(protocol::encode_welcome(w), protocol::server_frame_limits).value);
    REQUIRE(back);
    REQUIRE(back.value.statics.size() == statics);
    size_t i = 0;
    for (const world::body& b : g.state().bodies()) {
        if (!b.is_static()) continue;
        const protocol::static_body& s = back.value.statics[i++];
        CHECK(s.x == b.position.x());
        CHECK(s.y == b.position.y());
        CHECK(s.angle == b.angle);
        CHECK(s.shape == match::describe(g.state(), b, 7));
    }
}

TEST_CASE("the largest config of static chains makes a Welcome within the frame limit", "[match][shapes][limits]") {
    // Configs are at most max_config_bytes; the densest static geometry per byte is a chain of
    // short points. Its Welcome (the config's JSON as the server writes it, plus each segment's
    // pose, shape and two vertices) must still be a frame a client accepts.
    std::string text = R"({"size": [1000000, 1000], "bodies": [{"shape": {"type": "chain", "points": [)";
    for (int x = 0; text.size() + 40 < config::max_config_bytes; ++x) {
        if (x != 0) text += ',';
        text += '[' + std::to_string(x) + ",0]";
    }
    text += "]}}]}";
    auto parsed = config::parse_config_json(text);
    REQUIRE(parsed.ok());
    match::match g({}, parsed.value);
    const size_t segments = g.state().bodies().size();
    CHECK(segments > 100'000);
    const auto frame = protocol::encode_welcome(g.welcome_for(1, 1));
    INFO(segments << " segments, Welcome of " << frame.size() << " bytes");
    CHECK(frame.size() - protocol::frame_prefix_size <= protocol::max_server_frame_body);
    const auto verified = protocol::verify_message(frame, protocol::server_frame_limits);
    REQUIRE(verified);
    const auto back = protocol::decode_welcome(*verified.value);
    REQUIRE(back);
    CHECK(back.value.statics.size() == segments);
}

TEST_CASE("a world whose Welcome would exceed the frame limit does not start", "[match][shapes][limits]") {
    // Built directly, past the config file's limits: 600 000 static segments.
    world::world_config c;
    c.size = {1e6f, 1000};
    world::body_config chain;
    chain.shape.type = world::shape_type::chain;
    for (int x = 0; x <= 600'000; ++x) chain.shape.points.push_back({static_cast<float>(x), 0});
    c.bodies.push_back(chain);
    try {
        match::match g({}, c);
        FAIL("the match started");
    } catch (const std::invalid_argument& e) {
        CHECK_THAT(e.what(), Catch::Matchers::Contains("a Welcome of") &&
                                 Catch::Matchers::Contains("above the 16777216 a client accepts"));
    }
}
