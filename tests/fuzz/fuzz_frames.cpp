// Fuzz target: bytes from a client, through everything the server does with them before the
// world: framing (in uneven chunks), verification, then the match's admission and handling of
// every message (a fake connection stands in for the socket).
#include <cstddef>
#include <cstdint>
#include <span>

#include "protocol/decode.hpp"
#include "protocol/framing.hpp"
#include "protocol/verify.hpp"
#include "server/match/match.hpp"
#include "server/world/presets.hpp"

namespace {

struct null_connection : arena::match::connection {
    void send(arena::protocol::frame_bytes) override {}
    void send_snapshot(const arena::protocol::snapshot_encoder&, uint32_t) override {}
    void send_snapshot_frame(std::span<const uint8_t>) override {}
    void close(arena::protocol::RejectCode, std::string_view) override {}
    void close_with_bye(std::string_view) override {}
    std::string_view peer() const override { return "fuzz"; }
};

arena::world::world_config small_world() {
    arena::world::world_config c = arena::world::asteroids_preset();
    c.rocks.count = 4;
    return c;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace arena;
    static const world::world_config config = small_world();
    match::match game({}, config);
    null_connection client;
    game.connect(client);
    bool open = true;
    protocol::frame_reader reader;
    // The first byte picks the chunk size, so that prefixes and bodies get split anywhere.
    const size_t chunk = size ? 1 + data[0] % 17 : 1;
    size_t at = size ? 1 : 0;
    while (at < size && open) {
        const size_t n = std::min(chunk, size - at);
        at += reader.feed(std::span<const uint8_t>(data + at, n));
        if (reader.failed()) {
            game.reject(client, match::admission::unreadable(reader));
            break;
        }
        if (!reader.has_frame()) continue;
        auto message = protocol::verify_message(reader.frame(), protocol::client_frame_limits);
        if (message) {
            const protocol::Message& m = *message.value;
            // Admission and the match, as a transport drives them; a tick after each message.
            open = game.receive(client, m);
            game.tick();
            (void)protocol::decode_snapshot(m);
            (void)protocol::decode_welcome(m);
        } else {
            game.reject(client, match::admission::unverified(message.error));
            open = false;
        }
        reader.next();
    }
    game.tick();
    return 0;
}
