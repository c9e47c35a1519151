#include "server/host/intake.hpp"

#include "protocol/decode.hpp"
#include "protocol/verify.hpp"

namespace arena::host {

intake::intake(match_registry& matches, ops::process_counters& counters) : matches_(matches), counters_(counters) {}

intake_result intake::take(match::connection& from, std::span<const uint8_t> frame, std::optional<int64_t> arrival_ns,
                           int64_t held_ns) {
    // Verified before a field is read: bytes from a peer never reach the match unchecked.
    auto verified = protocol::verify_message(frame, protocol::client_frame_limits);
    if (!verified) {
        matches_.match_of(from).reject(from, match::admission::unverified(verified.error));
        return {};
    }
    ++counters_.messages_in;
    const protocol::Message& message = *verified.value;
    match::match* game = &matches_.match_of(from);
    // A Hello may name another match or a mode: the registry moves the connection there first.
    // One that does not decode is the match's to refuse.
    if (message.payload_type() == protocol::Payload::Hello) {
        if (auto hello = protocol::decode_hello(message)) {
            game = matches_.route_hello(from, hello.value);
            if (!game) return {false, &message};
        }
    }
    const bool go_on = arrival_ns ? game->receive(from, message, *arrival_ns, held_ns) : game->receive(from, message);
    return {go_on, &message};
}

void intake::refuse_unreadable(match::connection& from, const protocol::frame_reader& reader) {
    matches_.match_of(from).reject(from, match::admission::unreadable(reader));
}

void intake::refuse(match::connection& from, const match::rejection& why) {
    matches_.match_of(from).reject(from, why);
}

}  // namespace arena::host
