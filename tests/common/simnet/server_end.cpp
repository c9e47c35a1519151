#include "simnet/server_end.hpp"

#include "protocol/decode.hpp"
#include "protocol/verify.hpp"

namespace arena::simnet {

using protocol::Payload;
using protocol::RejectCode;

server_end::server_end(match::match& game, path& down, const sim_time& now, std::string peer)
    : game_(game), down_(down), now_(now), peer_(std::move(peer)) {}

void server_end::on_data(std::span<const std::uint8_t> data) {
    if (closed_) return;
    if (down_.kind() == link_kind::datagram) return on_frame(data);
    while (!data.empty() && !closed_) {
        data = data.subspan(reader_.feed(data));
        if (reader_.failed()) return close(RejectCode::bad_request, reader_.error());
        if (!reader_.has_frame()) return;
        on_frame(reader_.frame());
        reader_.next();
    }
}

void server_end::on_frame(std::span<const std::uint8_t> frame) {
    // A datagram is copied into the reader as a stream's bytes are: FlatBuffers wants the
    // frame 8-byte aligned.
    if (down_.kind() == link_kind::datagram) {
        if (reader_.feed(frame) != frame.size() || !reader_.has_frame())
            return close(RejectCode::bad_request, "a datagram that is not exactly one frame");
        frame = reader_.frame();
    }
    const auto verified = protocol::verify_message(frame, protocol::client_frame_limits);
    if (!verified) return close(RejectCode::bad_request, "frame failed verification: " + verified.error);
    dispatch(*verified.value);
    if (down_.kind() == link_kind::datagram && !closed_) reader_.next();
}

void server_end::dispatch(const protocol::Message& message) {
    switch (message.payload_type()) {
        case Payload::Hello: {
            if (player_id_ != 0) return close(RejectCode::bad_request, "a second Hello");
            const auto hello = protocol::decode_hello(message);
            if (!hello) return close(RejectCode::bad_request, hello.error);
            auto joined = game_.join(*this, hello.value, hello.value.token);
            if (auto* no = std::get_if<match::rejection>(&joined)) return close(no->code, no->reason);
            player_id_ = std::get<std::uint32_t>(joined);
            return;
        }
        case Payload::Input: {
            if (player_id_ == 0) return close(RejectCode::bad_request, "Input before Hello");
            const auto input = protocol::decode_input(message);
            if (!input) return close(RejectCode::bad_input, input.error);
            if (auto no = game_.receive_input(player_id_, input.value)) return close(no->code, no->reason);
            if (on_input) on_input(input.value);
            return;
        }
        case Payload::Ping: {
            if (player_id_ == 0) return close(RejectCode::bad_request, "Ping before Hello");
            const auto ping = protocol::decode_ping(message);
            if (!ping) return close(RejectCode::bad_request, ping.error);
            send(protocol::encode_pong(ping.value.client_time, game_.state().tick()));
            return;
        }
        case Payload::Bye: {
            const auto bye = protocol::decode_bye(message);
            const std::string reason = "client said bye: " + (bye ? bye.value.reason : std::string("(unreadable)"));
            if (player_id_ != 0) game_.leave(player_id_, *this, reason);
            close_after({}, reason);
            return;
        }
        default:
            close(RejectCode::bad_request,
                  "unexpected " + std::string(protocol::payload_name(message.payload_type())) + " from a client");
    }
}

void server_end::on_end() {
    if (closed_) return;
    if (player_id_ != 0) game_.leave(player_id_, *this, "connection closed", true);
    close_after({}, "connection closed");
}

void server_end::send(protocol::frame_bytes frame) {
    if (closed_) return;
    // The Welcome names the body: the tests map the world's inputs to this connection by it.
    if (const auto m = protocol::verify_message(frame, protocol::server_frame_limits);
        m && m.value->payload_type() == Payload::Welcome) {
        if (const auto w = protocol::decode_welcome(*m.value)) body_id_ = w.value.entity_id;
    }
    down_.send(frame, true, now_);
}

void server_end::send_snapshot(const protocol::snapshot_encoder& snapshot, std::uint32_t ack_sequence) {
    send_snapshot_frame(snapshot.frame_with_ack(ack_sequence));
}

void server_end::send_snapshot_frame(std::span<const std::uint8_t> frame) {
    if (closed_) return;
    if (on_snapshot_ack) {
        // Copied for alignment: the fan-out's frame lives in a builder's buffer.
        const protocol::frame_bytes copy(frame.begin(), frame.end());
        if (const auto m = protocol::verify_message(copy, protocol::server_frame_limits)) {
            if (const auto s = protocol::decode_snapshot(*m.value)) on_snapshot_ack(s.value.ack_sequence);
        }
    }
    down_.send(frame, false, now_);
}

void server_end::close(RejectCode code, std::string_view reason) {
    if (closed_) return;
    const std::string text = std::string(protocol::EnumNameRejectCode(code)) + ": " + std::string(reason);
    if (player_id_ != 0) game_.leave(player_id_, *this, text);
    close_after(protocol::encode_reject(code, reason), text);
}

void server_end::close_with_bye(std::string_view reason) {
    if (closed_) return;
    if (player_id_ != 0) game_.leave(player_id_, *this, reason);
    close_after(protocol::encode_bye(reason), std::string(reason));
}

void server_end::close_after(const protocol::frame_bytes& last_word, std::string reason) {
    closed_ = true;
    close_reason_ = std::move(reason);
    if (!last_word.empty()) down_.send(last_word, true, now_);
    down_.close(now_);
}

}  // namespace arena::simnet
