#pragma once
// The server's end of one simulated connection: what a transport does for the match, over a
// simulated path instead of a socket. Bytes (or datagrams) in are framed and handed to the
// intake (server/host/intake.hpp), which verifies them and hands them to the match; the match's frames go out on the
// downward path at once (a socket that always has room: no snapshot is ever replaced while waiting). It sees every
// Input the match accepts and every snapshot's ack, for the tests' checks.
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <string_view>

#include "protocol/framing.hpp"
#include "server/host/intake.hpp"
#include "server/match/match.hpp"
#include "simnet/path.hpp"

namespace arena::simnet {

class server_end : public match::connection {
public:
    // Frames go through `intake`, as a transport's do; the connection's match is the intake's.
    server_end(host::intake& intake, path& down, const sim_time& now, std::string peer);

    // The client connected: the match is handed this connection (it may refuse it).
    void open();
    // From the upward path.
    void on_data(std::span<const std::uint8_t> data);
    // The client's end of the connection arrived.
    void on_end();

    void send(protocol::frame_bytes frame) override;
    void send_snapshot(const protocol::snapshot_encoder& snapshot, std::uint32_t ack_sequence) override;
    void send_snapshot_frame(std::span<const std::uint8_t> frame) override;
    void close(protocol::RejectCode code, std::string_view reason) override;
    void close_with_bye(std::string_view reason) override;
    void close_with_result(std::string_view reason, const protocol::match_result& result) override;
    std::string_view peer() const override { return peer_; }

    [[nodiscard]] std::uint32_t player_id() const { return intake_.matches().match_of(*this).player_of(*this); }
    [[nodiscard]] std::uint32_t body_id() const { return body_id_; }  // from the Welcome sent
    [[nodiscard]] bool closed() const { return closed_; }
    [[nodiscard]] const std::string& close_reason() const { return close_reason_; }

    // Each Input the match took (sequence and values), and each snapshot's ack as it leaves.
    std::function<void(const protocol::input_msg&)> on_input;
    std::function<void(std::uint32_t ack_sequence)> on_snapshot_ack;

private:
    void on_frame(std::span<const std::uint8_t> frame);
    void close_after(const protocol::frame_bytes& last_word, std::string reason);

    host::intake& intake_;
    path& down_;
    const sim_time& now_;
    std::string peer_;
    protocol::frame_reader reader_;
    std::uint32_t body_id_ = 0;
    bool closed_ = false;
    std::string close_reason_;
};

}  // namespace arena::simnet
