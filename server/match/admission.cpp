#include "server/match/admission.hpp"

#include <algorithm>
#include <cmath>

#include "protocol/player_name.hpp"
#include "protocol/version.hpp"
#include "server/world/assert.hpp"

namespace arena::match {

using protocol::Payload;
using protocol::RejectCode;

namespace {

// Whole ticks covering `d`, at least one.
uint32_t ticks_covering(std::chrono::nanoseconds d, uint16_t tick_rate) {
    const double ticks = std::ceil(std::chrono::duration<double>(d).count() * tick_rate);
    return std::max<uint32_t>(1, static_cast<uint32_t>(ticks));
}

}  // namespace

admission::admission(const admission_limits& limits, uint16_t tick_rate, token_check check_token)
    : limits_(limits),
      tick_rate_(tick_rate),
      handshake_timeout_ticks_(ticks_covering(limits.handshake_timeout, tick_rate)),
      idle_timeout_ticks_(limits.idle_timeout.count() <= 0 ? 0 : ticks_covering(limits.idle_timeout, tick_rate)),
      check_token_(std::move(check_token)) {
    ARENA_ASSERT(tick_rate > 0, "the time-outs are counted in ticks");
}

uint32_t admission::input_limit() const {
    return limits_.max_inputs_per_second ? limits_.max_inputs_per_second : 2u * tick_rate_ + 10u;
}

uint32_t admission::connection_limit() const {
    // Every player twice (a reconnection while the old connection is still open), every spectator.
    return limits_.max_connections ? limits_.max_connections : 2 * limits_.max_players + limits_.max_spectators + 16;
}

uint32_t admission::pending_limit() const {
    if (limits_.max_pending_handshakes) return limits_.max_pending_handshakes;
    return std::max<uint32_t>(64, limits_.max_players + 16);
}

std::variant<admission::connection_verdict, rejection> admission::admit_connection(size_t open,
                                                                                   size_t awaiting_hello) const {
    // The others waiting (this one excluded) are what could make room.
    const size_t others_waiting = awaiting_hello - 1;
    if (open > connection_limit()) {
        if (others_waiting == 0) return rejection{RejectCode::server_full, "too many connections"};
        return connection_verdict::make_room;
    }
    if (awaiting_hello > pending_limit() && others_waiting > 0) return connection_verdict::make_room;
    return connection_verdict::admit;
}

rejection admission::waiting_evicted() {
    return {RejectCode::too_many_waiting, "too many connections waiting to say Hello; a newer one took this slot"};
}

rejection admission::unreadable(const protocol::frame_reader& reader) {
    const bool too_large = reader.failure_kind() == protocol::frame_reader::failure::too_large;
    return {too_large ? RejectCode::too_large : RejectCode::bad_request, std::string(reader.error())};
}

rejection admission::unverified(std::string_view error) {
    return {RejectCode::bad_request, "frame failed verification: " + std::string(error)};
}

admitted_message admission::admit_message(const client_standing& client, const protocol::Message& message) const {
    const bool joined = client.at == client_standing::stage::joined;
    switch (message.payload_type()) {
        case Payload::Hello: {
            if (joined) return rejection{RejectCode::bad_request, "a second Hello"};
            auto hello = protocol::decode_hello(message);
            if (!hello) return rejection{RejectCode::bad_request, hello.error};
            return hello_message{std::move(hello.value)};
        }
        case Payload::Input: {
            if (!joined) return rejection{RejectCode::bad_request, "Input before Hello"};
            if (client.spectator) return rejection{RejectCode::bad_request, "Input from a spectator, who has no body"};
            auto input = protocol::decode_input(message);
            if (!input) return rejection{RejectCode::bad_input, input.error};
            return input_message{input.value};
        }
        case Payload::Ping: {
            if (!joined) return rejection{RejectCode::bad_request, "Ping before Hello"};
            auto ping = protocol::decode_ping(message);
            if (!ping) return rejection{RejectCode::bad_request, ping.error};
            return ping_message{ping.value.client_time};
        }
        case Payload::Bye: {
            // The reason goes to the log as it is shown: escaped, so that it cannot forge a line.
            auto bye = protocol::decode_bye(message);
            return bye_message{bye ? protocol::printable_text(bye.value.reason) : std::string("(unreadable)")};
        }
        default:
            return rejection{
                RejectCode::bad_request,
                "unexpected " + std::string(protocol::payload_name(message.payload_type())) + " from a client"};
    }
}

std::variant<admitted_hello, rejection> admission::admit_hello(const protocol::hello_msg& hello, bool draining) const {
    if (draining) return rejection{RejectCode::shutting_down, "the server is shutting down"};
    if (hello.protocol_version != protocol::protocol_version)
        return rejection{RejectCode::version_mismatch, "protocol version " + std::to_string(hello.protocol_version) +
                                                           " is not supported; this server speaks " +
                                                           std::to_string(protocol::protocol_version)};
    // The one name rule (protocol/player_name.hpp): a name reaches log lines and other clients.
    if (auto problem = protocol::player_name_problem(hello.name, limits_.max_name_bytes))
        return rejection{RejectCode::bad_request, std::move(*problem)};
    if (hello.token.size() > limits_.max_token_bytes)
        return rejection{RejectCode::bad_request,
                         "token longer than " + std::to_string(limits_.max_token_bytes) + " bytes"};
    if (hello.match.size() > limits_.max_match_bytes || hello.mode.size() > limits_.max_match_bytes)
        return rejection{RejectCode::bad_request,
                         "match or mode longer than " + std::to_string(limits_.max_match_bytes) + " bytes"};
    // Open: the token is the client's own key. A spectator holds no identity: it has nothing
    // to reconnect to and takes nobody over.
    if (!check_token_) return admitted_hello{hello.name, hello.spectator ? "" : hello.token, hello.spectator};
    result<signed_token> signed_by = check_token_(hello.token);
    if (!signed_by) return rejection{RejectCode::unauthorized, std::move(signed_by.error)};
    const std::string& name = signed_by.value.name;
    if (auto problem = protocol::player_name_problem(name, limits_.max_name_bytes))
        return rejection{RejectCode::unauthorized, "the token's " + *problem};
    // The signed name is the player's identity, whatever name the Hello claims.
    return admitted_hello{name, hello.spectator ? "" : "signed:" + name, hello.spectator, signed_by.value.match};
}

std::optional<rejection> admission::admit_token_match(const admitted_hello& admitted, std::string_view match_id) {
    if (admitted.token_match.empty() || admitted.token_match == match_id) return std::nullopt;
    return rejection{RejectCode::unauthorized, "this token is good for match " + admitted.token_match + " only"};
}

std::variant<join_kind, rejection> admission::admit_join(std::optional<bool> same_identity_connected,
                                                         size_t live_players) const {
    if (same_identity_connected) return *same_identity_connected ? join_kind::takeover : join_kind::reconnect;
    if (live_players >= limits_.max_players)
        return rejection{RejectCode::server_full, "server full (" + std::to_string(limits_.max_players) + " players)"};
    return join_kind::new_player;
}

std::optional<rejection> admission::admit_spectator(size_t spectators) const {
    if (limits_.max_spectators == 0) return rejection{RejectCode::server_full, "this server admits no spectators"};
    if (spectators >= limits_.max_spectators)
        return rejection{RejectCode::server_full,
                         "server full (" + std::to_string(limits_.max_spectators) + " spectators)"};
    return std::nullopt;
}

std::variant<admitted_input, rejection> admission::admit_input(client_standing& client,
                                                               const protocol::input_msg& input, int64_t arrival_ns,
                                                               uint32_t tick) const {
    const double rate = input_limit();
    if (!client.inputs.take(arrival_ns, rate,
                            std::max(1.0, rate * std::chrono::duration<double>(limits_.input_burst).count())))
        return rejection{RejectCode::rate_limit, "more than " + std::to_string(input_limit()) + " inputs per second"};
    const world::player_input in{input.thrust, input.turn, input.buttons};
    if (auto problem = world::check_input(in)) return rejection{RejectCode::bad_input, *problem};
    for (const protocol::earlier_input& e : input.earlier)
        if (auto problem = world::check_input({e.thrust, e.turn, e.buttons}))
            return rejection{RejectCode::bad_input, "earlier input " + std::to_string(e.sequence) + ": " + *problem};
    client.last_input_tick = tick;
    if (input.sequence <= client.last_sequence) return admitted_input{true, {}, 0, {}, 0};
    // Decoding checked that the earlier sequences rise and stay below this one: those not taken
    // yet are taken now, in order, each once.
    // The moment of the view the input was made from; an earlier input was made a tick before
    // each later one (one input a tick), so from a view that much older.
    const uint64_t view = input.view_tick == 0 ? 0 : uint64_t{input.view_tick} * 256 + input.view_fraction;
    const auto earlier_view = [&](uint32_t sequence) {
        const uint64_t back = uint64_t{input.sequence - sequence} * 256;
        return view > back ? view - back : 0;
    };
    admitted_input out{false, in, view, {}};
    const uint32_t gap = input.sequence - client.last_sequence - 1;
    for (const protocol::earlier_input& e : input.earlier) {
        if (e.sequence <= client.last_sequence) continue;
        out.recovered.push_back({e.sequence, {e.thrust, e.turn, e.buttons}, earlier_view(e.sequence)});
        client.last_sequence = e.sequence;
    }
    out.lost = gap - out.recovered.size();
    client.last_sequence = input.sequence;
    return out;
}

std::optional<rejection> admission::admit_ping(client_standing& client, int64_t arrival_ns, uint32_t tick) const {
    if (client.pings.take(arrival_ns, limits_.max_pings_per_second, std::max<uint32_t>(1, limits_.ping_burst))) {
        if (client.spectator) client.last_input_tick = tick;
        return std::nullopt;
    }
    return rejection{RejectCode::ping_limit, "more than " + std::to_string(limits_.ping_burst) + " Pings at once or " +
                                                 std::to_string(limits_.max_pings_per_second) + " per second"};
}

std::optional<rejection> admission::check_on_tick(const client_standing& client, uint32_t tick) const {
    if (client.at == client_standing::stage::awaiting_hello && tick - client.connected_tick >= handshake_timeout_ticks_)
        return rejection{RejectCode::timeout, "no Hello within the handshake timeout"};
    if (client.at == client_standing::stage::joined && idle_timeout_ticks_ != 0 &&
        tick - client.last_input_tick >= idle_timeout_ticks_)
        return rejection{RejectCode::timeout,
                         client.spectator ? "no Ping within the idle timeout" : "no Input within the idle timeout"};
    return std::nullopt;
}

}  // namespace arena::match
