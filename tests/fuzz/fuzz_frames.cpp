// Fuzz target: bytes from clients, through everything the server does with them before the
// world: framing (in uneven chunks), verification, then the match's admission and handling of
// every message. Up to eight connections from three addresses share the input (chunks go to
// them in turn), with small limits, so that the handshake slots overflow and evict, players
// take each other over, drop into the reconnect grace and give it up, and time out; a closed
// connection is replaced by a new one. Fake connections stand in for sockets.
//
// The first byte picks the chunk size (low four bits) and the number of connections (high
// bits): the seeds written for one connection (first byte below 16) still mean what they did.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "protocol/decode.hpp"
#include "protocol/framing.hpp"
#include "protocol/shapes.hpp"
#include "protocol/verify.hpp"
#include "server/match/match.hpp"
#include "server/world/presets.hpp"

namespace {

struct fuzz_connection : arena::match::connection {
    std::string from;
    bool closed = false;
    arena::protocol::frame_reader reader;
    void send(arena::protocol::frame_bytes) override {}
    void send_snapshot(const arena::protocol::snapshot_encoder&, uint32_t) override {}
    void send_snapshot_frame(std::span<const uint8_t>) override {}
    void close(arena::protocol::RejectCode, std::string_view) override { closed = true; }
    void close_with_bye(std::string_view) override { closed = true; }
    std::string_view peer() const override { return from; }
};

arena::world::world_config small_world() {
    arena::world::world_config c = arena::world::asteroids_preset();
    c.rocks.count = 4;
    return c;
}

// Limits small enough for a short input to reach every one of them.
arena::match::match_config small_limits() {
    arena::match::match_config c;
    c.admission.max_players = 3;
    c.admission.max_spectators = 2;
    c.admission.max_connections = 6;
    c.admission.max_pending_handshakes = 2;
    c.admission.handshake_timeout = std::chrono::milliseconds(100);
    c.admission.idle_timeout = std::chrono::milliseconds(200);
    c.reconnect_grace_s = 0.3;
    return c;
}

// What must hold whatever the clients sent.
void check(const arena::match::match& game) {
    if (game.live_player_count() > game.config().admission.max_players) __builtin_trap();
    if (game.player_count() > game.config().admission.max_players) __builtin_trap();
    if (game.spectator_count() > game.config().admission.max_spectators) __builtin_trap();
    if (game.connection_count() > game.rules().connection_limit()) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace arena;
    static const world::world_config config = small_world();
    match::match game(small_limits(), config);
    const size_t chunk = size ? 1 + (data[0] & 0x0f) : 1;
    const size_t count = size ? 1 + (data[0] >> 4) % 8 : 1;
    std::array<fuzz_connection, 8> pool;
    for (size_t k = 0; k < count; ++k) {
        pool[k].from = "10.0.0." + std::to_string(k % 3) + ":" + std::to_string(1000 + k);
        if (!game.connect(pool[k])) pool[k].closed = true;
    }
    int64_t now_ns = 0;
    size_t turn = 0;
    for (size_t at = size ? 1 : 0; at < size; ++turn) {
        fuzz_connection& c = pool[turn % count];
        std::span<const uint8_t> bytes(data + at, std::min(chunk, size - at));
        at += bytes.size();
        now_ns += static_cast<int64_t>(bytes.size()) * 1'000'000;  // arrival times move with the bytes
        if (c.closed) {  // a new connection from the same address takes its place
            c.closed = false;
            c.reader = protocol::frame_reader();
            if (!game.connect(c)) c.closed = true;
        } else if (turn % 61 == 60) {  // now and then a connection drops without a word
            game.disconnect(c, {match::close_cause::kind::connection_closed, {}, {}});
            c.closed = true;
        }
        while (!c.closed && !bytes.empty()) {
            bytes = bytes.subspan(c.reader.feed(bytes));
            if (c.reader.failed()) {
                game.reject(c, match::admission::unreadable(c.reader));
                c.closed = true;
                break;
            }
            if (!c.reader.has_frame()) break;
            auto message = protocol::verify_message(c.reader.frame(), protocol::client_frame_limits);
            if (message) {
                const protocol::Message& m = *message.value;
                // Admission and the match, as a transport drives them.
                if (!game.receive(c, m, now_ns)) c.closed = true;
                if (const auto snapshot = protocol::decode_snapshot(m)) {
                    std::vector<protocol::shape_desc> shapes;
                    (void)protocol::read_shapes(snapshot.value.shapes, snapshot.value.shape_vertices, shapes);
                }
                (void)protocol::decode_welcome(m);
            } else {
                game.reject(c, match::admission::unverified(message.error));
                c.closed = true;
            }
            c.reader.next();
        }
        game.tick();  // a tick after each chunk
        check(game);
    }
    game.tick();
    check(game);
    return 0;
}
