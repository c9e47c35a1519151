// Body shapes on the wire (protocol/shapes.hpp): exact round trips in Snapshots of both kinds
// and in the Welcome, the checks read_shapes() makes, and frames that stay within the
// verifier's table limits however many shapes they carry.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <vector>

#include "protocol/decode.hpp"
#include "protocol/messages.hpp"
#include "protocol/shapes.hpp"
#include "protocol/snapshot.hpp"
#include "protocol/verify.hpp"

namespace ap = arena::protocol;

namespace {

ap::shape_desc circle(std::uint32_t id, float r) {
    ap::shape_desc d;
    d.id = id;
    d.type = ap::ShapeType::circle;
    d.vertex_count = 1;
    d.radius = r;
    return d;
}

ap::shape_desc box(std::uint32_t id, std::uint8_t kind, float hx, float hy, float rounding) {
    ap::shape_desc d;
    d.id = id;
    d.kind = kind;
    d.type = ap::ShapeType::polygon;
    d.vertex_count = 4;
    d.radius = rounding;
    const float xy[] = {-hx, -hy, hx, -hy, hx, hy, -hx, hy};
    for (int i = 0; i < 8; ++i) d.xy[i] = xy[i];
    return d;
}

ap::shape_desc segment(std::uint32_t id, float half) {
    ap::shape_desc d;
    d.id = id;
    d.type = ap::ShapeType::segment;
    d.vertex_count = 2;
    d.radius = 0;
    d.xy[0] = -half;
    d.xy[2] = half;
    return d;
}

std::vector<ap::shape_desc> mixed_shapes() {
    ap::shape_desc octagon;
    octagon.id = 9;
    octagon.kind = 2;
    octagon.type = ap::ShapeType::polygon;
    octagon.vertex_count = 8;
    octagon.radius = 0;
    for (int i = 0; i < 16; ++i) octagon.xy[i] = 0.25f * static_cast<float>(i) - 1.5f;
    ap::shape_desc capsule;
    capsule.id = 12;
    capsule.kind = 255;
    capsule.type = ap::ShapeType::capsule;
    capsule.vertex_count = 2;
    capsule.radius = 0.3f;
    capsule.xy[0] = -0.5f;
    capsule.xy[2] = 0.5f;
    return {circle(3, 0.75f), box(5, 1, 0.5f, 0.25f, 0.05f), octagon, capsule, segment(40, 3.0f)};
}

const ap::Message& verified(const std::vector<std::uint8_t>& frame) {
    const auto v = ap::verify_message(frame, ap::server_frame_limits);
    INFO(v.error);
    REQUIRE(v);
    return *v.value;
}

std::vector<ap::shape_desc> shapes_of(const ap::snapshot_view& s) {
    std::vector<ap::shape_desc> out;
    const std::string problem = ap::read_shapes(s.shapes, s.shape_vertices, out);
    INFO(problem);
    REQUIRE(problem.empty());
    return out;
}

}  // namespace

TEST_CASE("Shapes round-trip exactly in full, delta and shared snapshots", "[protocol][shapes]") {
    const std::vector<ap::shape_desc> shapes = mixed_shapes();
    ap::shape_list list;
    for (const ap::shape_desc& d : shapes) list.append(d);
    REQUIRE(list.wire_bytes() == 5 * 12 + (1 + 4 + 8 + 2 + 2) * 8);

    flatbuffers::FlatBufferBuilder fbb;
    const std::vector<ap::BodyState> bodies{{3, 0, 1, 2, 3, 4, 0.5f, 0.25f}};
    const auto full = ap::encode_snapshot(fbb, 7, 2, bodies, &list);
    const std::vector<std::uint8_t> full_frame(full.begin(), full.end());
    const auto full_view = ap::decode_snapshot(verified(full_frame));
    REQUIRE(full_view);
    CHECK(full_view.value.bodies.size() == 1);
    CHECK(shapes_of(full_view.value) == shapes);

    const std::vector<std::uint8_t> delta_bytes{1, 2, 3};
    const auto delta = ap::encode_delta_snapshot(fbb, 8, 2, 4, delta_bytes, &list);
    const std::vector<std::uint8_t> delta_frame(delta.begin(), delta.end());
    const auto delta_view = ap::decode_snapshot(verified(delta_frame));
    REQUIRE(delta_view);
    CHECK(delta_view.value.is_delta);
    CHECK(delta_view.value.baseline_tick == 4);
    CHECK(shapes_of(delta_view.value) == shapes);

    ap::snapshot_encoder shared;
    shared.build(9, bodies, &list);
    const auto patched = shared.frame_with_ack(77);
    const auto shared_view = ap::decode_snapshot(verified(patched));
    REQUIRE(shared_view);
    CHECK(shared_view.value.ack_sequence == 77);
    CHECK(shapes_of(shared_view.value) == shapes);
}

TEST_CASE("A snapshot without shapes is the frame it was before shapes existed", "[protocol][shapes]") {
    flatbuffers::FlatBufferBuilder a, b;
    const std::vector<ap::BodyState> bodies{{3, 0, 1, 2, 3, 4, 0.5f, 0.25f}};
    const ap::shape_list empty;
    const auto without = ap::encode_snapshot(a, 7, 2, bodies);
    const auto with_empty = ap::encode_snapshot(b, 7, 2, bodies, &empty);
    CHECK(std::vector<std::uint8_t>(without.begin(), without.end()) ==
          std::vector<std::uint8_t>(with_empty.begin(), with_empty.end()));
    // The view points into the frame's bytes: they must outlive it.
    const std::vector<std::uint8_t> without_bytes(without.begin(), without.end());
    const auto view = ap::decode_snapshot(verified(without_bytes));
    REQUIRE(view);
    CHECK(view.value.shapes == nullptr);
    CHECK(shapes_of(view.value).empty());
}

TEST_CASE("Thousands of shapes stay within the verifier's table limits", "[protocol][shapes]") {
    // Shapes are structs in vectors, not tables: the depth and table limits of 4 that every
    // client applies (verify.hpp) hold whatever their number.
    ap::shape_list list;
    for (std::uint32_t i = 1; i <= 5000; ++i) list.append(i % 2 ? circle(i, 1) : box(i, 3, 1, 2, 0));
    flatbuffers::FlatBufferBuilder fbb;
    const auto frame = ap::encode_delta_snapshot(fbb, 8, 2, 0, std::vector<std::uint8_t>{1}, &list);
    const std::vector<std::uint8_t> bytes(frame.begin(), frame.end());
    static_assert(ap::server_frame_limits.max_depth == 4 && ap::server_frame_limits.max_tables == 4);
    const auto v = ap::verify_message(bytes, ap::server_frame_limits);
    INFO(v.error);
    REQUIRE(v);
    const auto view = ap::decode_snapshot(*v.value);
    REQUIRE(view);
    CHECK(shapes_of(view.value).size() == 5000);
}

TEST_CASE("The Welcome's static geometry round-trips, and a world without statics sends none", "[protocol][shapes]") {
    ap::welcome_info w;
    w.player_id = 1;
    w.entity_id = 2;
    w.tick_rate = 60;
    w.snapshot_rate = 20;
    w.world_config = "{}";
    const auto bare = ap::decode_welcome(verified(ap::encode_welcome(w)));
    REQUIRE(bare);
    CHECK(bare.value.statics.empty());
    CHECK(bare.value == w);

    w.statics.push_back({-3.5f, 2.0f, 0.25f, segment(4, 10)});
    w.statics.push_back({0.0f, -1.0f, 0.0f, box(6, 7, 20, 1, 0)});
    const auto frame = ap::encode_welcome(w);
    const auto back = ap::decode_welcome(verified(frame));
    INFO(back.error);
    REQUIRE(back);
    CHECK(back.value == w);
}

TEST_CASE("read_shapes refuses counts that do not add up, misfit types and non-finite values", "[protocol][shapes]") {
    const auto problem_with = [](std::vector<ap::BodyShape> shapes, std::vector<ap::ShapeVertex> vertices) {
        flatbuffers::FlatBufferBuilder fbb;
        const auto s = fbb.CreateVectorOfStructs(shapes.data(), shapes.size());
        const auto v = fbb.CreateVectorOfStructs(vertices.data(), vertices.size());
        fbb.Finish(ap::CreateSnapshot(fbb, 1, 0, 0, 0, 0, s, v));
        const auto* snapshot = flatbuffers::GetRoot<ap::Snapshot>(fbb.GetBufferPointer());
        std::vector<ap::shape_desc> out{circle(99, 1)};
        const std::string problem = ap::read_shapes(snapshot->shapes(), snapshot->shape_vertices(), out);
        if (!problem.empty()) CHECK(out.size() == 1);  // unchanged on a refusal
        return problem;
    };
    const ap::ShapeVertex o(0, 0);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    CHECK(problem_with({{1, 0, ap::ShapeType::circle, 1, 1.0f}}, {o}).empty());
    CHECK(problem_with({{1, 0, ap::ShapeType::circle, 1, 1.0f}}, {o, o}) == "the shapes name 1 vertices, 2 are given");
    CHECK(problem_with({{1, 0, ap::ShapeType::circle, 2, 1.0f}}, {o, o}) ==
          "shape 0 (body 1): 2 vertices do not fit its type 0");
    CHECK(problem_with({{1, 0, ap::ShapeType::polygon, 9, 0.0f}}, std::vector<ap::ShapeVertex>(9, o)) ==
          "shape 0 (body 1): 9 vertices do not fit its type 2");
    CHECK(problem_with({{1, 0, ap::ShapeType::capsule, 2, 1.0f}, {2, 0, ap::ShapeType::segment, 2, 0.0f}}, {o, o, o}) ==
          "shape 1 (body 2): the shapes name more vertices than the 3 given");
    CHECK(problem_with({{1, 0, ap::ShapeType::circle, 1, -1.0f}}, {o}) ==
          "shape 0 (body 1): radius is not a finite number ≥ 0");
    CHECK(problem_with({{1, 0, ap::ShapeType::circle, 1, 1.0f}}, {{nan, 0}}) ==
          "shape 0 (body 1): a vertex is not finite");
    // A type from a newer server: its vertices are skipped by their count.
    CHECK(problem_with({{1, 0, static_cast<ap::ShapeType>(9), 5, 1.0f}, {2, 0, ap::ShapeType::circle, 1, 1.0f}},
                       std::vector<ap::ShapeVertex>(6, o))
              .empty());
}

TEST_CASE("decode_welcome refuses static geometry that does not line up", "[protocol][shapes]") {
    ap::welcome_info w;
    w.statics.push_back({0, 0, 0, segment(4, 10)});
    auto frame = ap::encode_welcome(w);
    // Make the pose name another body than its shape: the pose vector holds id 4 once.
    const ap::Message& m = verified(frame);
    auto* poses = const_cast<flatbuffers::Vector<const ap::BodyState*>*>(m.payload_as_Welcome()->static_bodies());
    REQUIRE(poses != nullptr);
    const_cast<ap::BodyState*>(poses->Get(0))->mutate_id(5);
    const auto back = ap::decode_welcome(verified(frame));
    CHECK_FALSE(back);
    CHECK(back.error == "Welcome: static_bodies[0] is body 5, its shape is body 4");
}

TEST_CASE("Shot origins ride with their shapes and round-trip exactly, and a non-finite one is refused",
          "[protocol][shapes][shots]") {
    ap::shape_list list;
    list.append(circle(5, 0.2f));
    list.origins.emplace_back(5, 2, 41, 10.5f, -3.25f, 40.0f, 0.125f);
    REQUIRE(list.wire_bytes() == 12 + 8 + 28);
    flatbuffers::FlatBufferBuilder fbb;
    const auto frame = ap::encode_delta_snapshot(fbb, 8, 41, 0, std::vector<std::uint8_t>{1}, &list);
    // The view points into the frame's bytes: they must outlive it.
    const std::vector<std::uint8_t> bytes(frame.begin(), frame.end());
    const auto view = ap::decode_snapshot(verified(bytes));
    REQUIRE(view);
    REQUIRE(view.value.shot_origins.size() == 1);
    const ap::ShotOrigin& o = view.value.shot_origins[0];
    CHECK(o.body_id() == 5);
    CHECK(o.owner() == 2);
    CHECK(o.input_sequence() == 41);
    CHECK(o.x() == 10.5f);
    CHECK(o.y() == -3.25f);
    CHECK(o.vx() == 40.0f);
    CHECK(o.vy() == 0.125f);

    // Shapes without origins leave the field out.
    ap::shape_list plain;
    plain.append(circle(6, 1));
    const auto without = ap::encode_delta_snapshot(fbb, 9, 41, 0, std::vector<std::uint8_t>{1}, &plain);
    const std::vector<std::uint8_t> without_bytes(without.begin(), without.end());
    const auto plain_view = ap::decode_snapshot(verified(without_bytes));
    REQUIRE(plain_view);
    CHECK(plain_view.value.table->shot_origins() == nullptr);

    list.origins[0] = ap::ShotOrigin(5, 2, 41, 10.5f, std::numeric_limits<float>::quiet_NaN(), 40.0f, 0.125f);
    const auto bad = ap::encode_delta_snapshot(fbb, 10, 41, 0, std::vector<std::uint8_t>{1}, &list);
    const std::vector<std::uint8_t> bad_bytes(bad.begin(), bad.end());
    const auto refused = ap::decode_snapshot(verified(bad_bytes));
    REQUIRE_FALSE(refused);
    CHECK(refused.error == "the shot origin of body 5 is not finite");
}
