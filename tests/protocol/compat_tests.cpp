// Old clients keep working (protocol/README.md, "Schema evolution"): frames that carry the
// shape fields, read with the code generated from the schema as it was before them
// (data/arena_v1.fbs), verify under the old client's limits and read as they always did.
#include <catch2/catch.hpp>

#include <vector>

#include "arena_v1_generated.h"
#include "protocol/messages.hpp"
#include "protocol/snapshot.hpp"

namespace ap = arena::protocol;
namespace old = arena::protocol_v1;

namespace {

// What an old client did with a frame: the FlatBuffers Verifier with the limits verify.hpp
// has always applied (depth 4, 4 tables), then the size-prefixed root.
// The result points into `frame`: a temporary would be gone before the caller reads it.
const old::Message* old_read(std::vector<std::uint8_t>&& frame) = delete;
const old::Message* old_read(const std::vector<std::uint8_t>& frame) {
    flatbuffers::Verifier::Options options;
    options.max_depth = 4;
    options.max_tables = 4;
    options.check_alignment = true;
    flatbuffers::Verifier verifier(frame.data(), frame.size(), options);
    REQUIRE(old::VerifySizePrefixedMessageBuffer(verifier));
    return old::GetSizePrefixedMessage(frame.data());
}

ap::shape_list some_shapes() {
    ap::shape_list list;
    for (std::uint32_t id = 1; id <= 40; ++id) {
        ap::shape_desc d;
        d.id = id;
        d.kind = static_cast<std::uint8_t>(id % 3);
        d.type = id % 2 ? ap::ShapeType::circle : ap::ShapeType::polygon;
        d.vertex_count = id % 2 ? 1 : 5;
        d.radius = 0.5f;
        for (int i = 0; i < 10; ++i) d.xy[i] = static_cast<float>(i) - 4.0f;
        list.append(d);
        // Some of them bullets, whose origins (appended since) an old client skips unread.
        if (id % 3 == 0) list.origins.emplace_back(id, 7, 100 + id, 1.0f, 2.0f, 40.0f, 0.0f);
    }
    return list;
}

std::vector<ap::BodyState> some_bodies() {
    std::vector<ap::BodyState> bodies;
    for (std::uint32_t id = 1; id <= 40; ++id) bodies.emplace_back(id, id % 4, 1.0f * id, -2.0f, 3, 4, 0.5f, 0.25f);
    return bodies;
}

}  // namespace

TEST_CASE("An old client reads a Welcome carrying static geometry", "[protocol][compat]") {
    ap::welcome_info w;
    w.player_id = 3;
    w.entity_id = 17;
    w.tick = 99;
    w.tick_rate = 60;
    w.snapshot_rate = 20;
    w.preset = "platformer";
    w.world_config = "{\"preset\": \"platformer\"}";
    w.world_config_hash = 0x1234;
    w.world_version = 2;
    w.view_radius = 50;
    for (const ap::BodyShape& s : some_shapes().shapes) {
        ap::static_body b;
        b.x = 1;
        b.shape.id = s.id();
        b.shape.type = ap::ShapeType::segment;
        b.shape.vertex_count = 2;
        w.statics.push_back(b);
    }
    const auto frame = ap::encode_welcome(w);
    const old::Message* m = old_read(frame);
    REQUIRE(m->payload_type() == old::Payload::Welcome);
    const old::Welcome* t = m->payload_as_Welcome();
    CHECK(t->player_id() == 3);
    CHECK(t->entity_id() == 17);
    CHECK(t->tick() == 99);
    CHECK(t->preset()->str() == "platformer");
    CHECK(t->world_config()->str() == w.world_config);
    CHECK(t->world_version() == 2);
    CHECK(t->view_radius() == 50);
}

TEST_CASE("An old client reads snapshots carrying shapes: full, shared with its ack, delta", "[protocol][compat]") {
    const ap::shape_list shapes = some_shapes();
    const std::vector<ap::BodyState> bodies = some_bodies();
    flatbuffers::FlatBufferBuilder fbb;

    const auto full = ap::encode_snapshot(fbb, 12, 5, bodies, &shapes);
    // Each frame is kept in a named vector: what old_read returns points into it.
    const std::vector<std::uint8_t> full_frame(full.begin(), full.end());
    const old::Snapshot* s = old_read(full_frame)->payload_as_Snapshot();
    REQUIRE(s != nullptr);
    CHECK(s->tick() == 12);
    CHECK(s->ack_sequence() == 5);
    REQUIRE(s->bodies()->size() == bodies.size());
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const old::BodyState& b = *s->bodies()->Get(static_cast<flatbuffers::uoffset_t>(i));
        CHECK(b.id() == bodies[i].id());
        CHECK(b.x() == bodies[i].x());
        CHECK(b.angular_velocity() == bodies[i].angular_velocity());
    }

    ap::snapshot_encoder shared;
    shared.build(13, bodies, &shapes);
    const std::vector<std::uint8_t> patched_frame = shared.frame_with_ack(41);
    const old::Snapshot* patched = old_read(patched_frame)->payload_as_Snapshot();
    REQUIRE(patched != nullptr);
    CHECK(patched->tick() == 13);
    CHECK(patched->ack_sequence() == 41);
    CHECK(patched->bodies()->size() == bodies.size());

    const std::vector<std::uint8_t> codec{9, 8, 7, 6};
    const auto delta = ap::encode_delta_snapshot(fbb, 14, 6, 11, codec, &shapes);
    const std::vector<std::uint8_t> delta_frame(delta.begin(), delta.end());
    const old::Snapshot* d = old_read(delta_frame)->payload_as_Snapshot();
    REQUIRE(d != nullptr);
    CHECK(d->baseline_tick() == 11);
    REQUIRE(d->delta() != nullptr);
    CHECK(std::vector<std::uint8_t>(d->delta()->begin(), d->delta()->end()) == codec);
}

namespace {

ap::game_list some_game() {
    ap::game_list g;
    for (std::uint32_t p = 1; p <= 32; ++p) {
        g.players.push_back({p, 20 * p, p % 3, p % 2, 7 * p, 3 * p, 2, ap::PlayerState::respawning});
        g.name_ids.push_back(p);
        g.names.push_back("bot-" + std::to_string(p));
    }
    for (std::uint32_t k = 1; k <= 20; ++k)
        g.events.push_back({k, 100 + k, ap::GameEventKind::ship_destroyed, 0, k, k + 1, 300 + k, 0});
    return g;
}

}  // namespace

TEST_CASE("An old client reads snapshots carrying the game: lines, names, events", "[protocol][compat]") {
    const ap::shape_list shapes = some_shapes();
    const ap::game_list game = some_game();
    const std::vector<ap::BodyState> bodies = some_bodies();
    flatbuffers::FlatBufferBuilder fbb;

    const auto full = ap::encode_snapshot(fbb, 12, 5, bodies, &shapes, &game);
    const std::vector<std::uint8_t> full_frame(full.begin(), full.end());
    const old::Snapshot* s = old_read(full_frame)->payload_as_Snapshot();
    REQUIRE(s != nullptr);
    CHECK(s->ack_sequence() == 5);
    REQUIRE(s->bodies()->size() == bodies.size());
    CHECK(s->bodies()->Get(39)->x() == bodies[39].x());

    ap::snapshot_encoder shared;
    shared.build(13, bodies, &shapes, &game);
    const std::vector<std::uint8_t> patched_frame = shared.frame_with_ack(41);
    const old::Snapshot* patched = old_read(patched_frame)->payload_as_Snapshot();
    REQUIRE(patched != nullptr);
    CHECK(patched->ack_sequence() == 41);

    const std::vector<std::uint8_t> codec{9, 8, 7, 6};
    const auto delta = ap::encode_delta_snapshot(fbb, 14, 6, 11, codec, &shapes, &game);
    const std::vector<std::uint8_t> delta_frame(delta.begin(), delta.end());
    const old::Snapshot* d = old_read(delta_frame)->payload_as_Snapshot();
    REQUIRE(d != nullptr);
    CHECK(d->baseline_tick() == 11);
    CHECK(std::vector<std::uint8_t>(d->delta()->begin(), d->delta()->end()) == codec);
}

TEST_CASE("An old client reads the Bye that ends a match as a Bye", "[protocol][compat]") {
    ap::match_result r;
    r.over = true;
    r.winner = 7;
    const ap::game_list game = some_game();
    r.scoreboard = game.players;
    r.names = game.names;
    const auto frame = ap::encode_bye("match over", &r);
    const old::Message* m = old_read(frame);
    REQUIRE(m->payload_type() == old::Payload::Bye);
    CHECK(m->payload_as_Bye()->reason()->str() == "match over");
}
