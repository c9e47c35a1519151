#pragma once
// One WebSocket client (/ws on the HTTP port): the match's connection, like a TCP session,
// over Beast's websocket stream. Each binary message is exactly one size-prefixed frame,
// framed by the same frame_reader as TCP (its prefix is checked before the body is kept),
// verified with the same limits and answered with the same Reject codes. Output is TCP's:
// control frames in order up to a limit, one snapshot slot that a newer snapshot replaces,
// written by one writer coroutine. WebSocket's own abuse: a message over the frame limit is
// refused by Beast's read_message_max before it is buffered; pings are rate-limited (each
// costs a pong); text messages are refused; permessage-deflate is off (no compression bomb).
// Included only by ws_session.cpp and web_transport.cpp: Beast is heavy to compile.
#include <boost/asio.hpp>
#include <boost/beast/core/tcp_stream.hpp>
#include <boost/beast/http/empty_body.hpp>
#include <boost/beast/http/message.hpp>
#include <boost/beast/websocket/stream.hpp>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "protocol/framing.hpp"
#include "server/match/connection.hpp"
#include "server/match/match.hpp"
#include "server/match/token_bucket.hpp"
#include "server/net/bounded_output.hpp"

namespace arena::net {

class web_transport;

class ws_session : public match::connection, public std::enable_shared_from_this<ws_session> {
public:
    using request = boost::beast::http::request<boost::beast::http::empty_body>;

    ws_session(boost::beast::tcp_stream stream, web_transport& owner, uint64_t id, std::string peer);

    // Answers the upgrade `upgrade`, hands the connection to the match and reads until it ends.
    // leftover: bytes the client sent after the request head (its first frames), read first.
    boost::asio::awaitable<void> run(request upgrade, std::vector<uint8_t> leftover);

    void send(protocol::frame_bytes frame) override;
    void send_snapshot(const protocol::snapshot_encoder& snapshot, uint32_t ack_sequence) override;
    void send_snapshot_frame(std::span<const uint8_t> frame) override;
    void close(protocol::RejectCode code, std::string_view reason) override;
    void close_with_bye(std::string_view reason) override;
    void close_with_result(std::string_view reason, const protocol::match_result& result) override;
    std::string_view peer() const override { return peer_; }

    int64_t stalled_ns(int64_t now_ns) const { return output_.stalled_ns(now_ns); }
    uint64_t id() const { return id_; }
    bool closing() const { return closing_; }

private:
    boost::asio::awaitable<void> reader();
    boost::asio::awaitable<void> writer();
    // The match this session belongs to (the host's registry says which).
    match::match& game();
    // The bytes of one read (part of a message): framed, handed to the intake; false: stop.
    bool take(std::span<const uint8_t> data, bool message_done);
    void reject_later(match::rejection why);
    void close_after(protocol::frame_bytes last_frame);
    void close_now();

    boost::beast::websocket::stream<boost::beast::tcp_stream> ws_;
    web_transport& owner_;
    uint64_t id_;
    std::string peer_;
    protocol::frame_reader reader_;
    bool frame_in_message_ = false;  // the current message already held its one frame
    match::token_bucket pings_;
    bool ping_refused_ = false;
    bounded_output output_;
    bool opened_ = false;  // handed to the match (and counted)
    bool closing_ = false;
    bool closed_ = false;
    boost::asio::steady_timer wake_;
    boost::asio::steady_timer linger_;
};

}  // namespace arena::net
