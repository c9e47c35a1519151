#include "simnet/server_end.hpp"

#include "protocol/decode.hpp"
#include "protocol/verify.hpp"

namespace arena::simnet {

using protocol::Payload;
using protocol::RejectCode;

server_end::server_end(host::intake& intake, path& down, const sim_time& now, std::string peer)
    : intake_(intake), down_(down), now_(now), peer_(std::move(peer)) {}

void server_end::open() {
    intake_.matches().match_of(*this).connect(*this);
}

void server_end::on_data(std::span<const std::uint8_t> data) {
    if (closed_) return;
    if (down_.kind() == link_kind::datagram) return on_frame(data);
    while (!data.empty() && !closed_) {
        data = data.subspan(reader_.feed(data));
        if (reader_.failed()) return intake_.refuse_unreadable(*this, reader_);
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
            return intake_.refuse(*this, {RejectCode::bad_request, "a datagram that is not exactly one frame"});
        frame = reader_.frame();
    }
    // No clock here: the match takes the message as arrived at its current tick's time.
    const host::intake_result taken = intake_.take(*this, frame, std::nullopt);
    if (taken.go_on) {
        // The match took it (a stale one included): the tests' ledger sees what it was given.
        if (taken.message->payload_type() == Payload::Input && on_input)
            on_input(protocol::decode_input(*taken.message).value);
    } else if (taken.message != nullptr && !closed_) {
        // The client said Bye: the match let it go, and the connection closes without a word.
        const auto bye = protocol::decode_bye(*taken.message);
        close_after({}, "client said bye: " + (bye ? bye.value.reason : std::string("(unreadable)")));
    }
    if (down_.kind() == link_kind::datagram && !closed_) reader_.next();
}

void server_end::on_end() {
    if (closed_) return;
    intake_.matches().match_of(*this).disconnect(*this, {match::close_cause::kind::connection_closed, {}, {}});
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
    // The match already counted this and let the player go.
    const std::string text = std::string(protocol::EnumNameRejectCode(code)) + ": " + std::string(reason);
    close_after(protocol::encode_reject(code, reason), text);
}

void server_end::close_with_bye(std::string_view reason) {
    if (closed_) return;
    close_after(protocol::encode_bye(reason), std::string(reason));
}

void server_end::close_with_result(std::string_view reason, const protocol::match_result& result) {
    if (closed_) return;
    close_after(protocol::encode_bye(reason, &result), std::string(reason));
}

void server_end::close_after(const protocol::frame_bytes& last_word, std::string reason) {
    closed_ = true;
    close_reason_ = std::move(reason);
    if (!last_word.empty()) down_.send(last_word, true, now_);
    down_.close(now_);
}

}  // namespace arena::simnet
