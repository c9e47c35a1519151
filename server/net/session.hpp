#pragma once
// One TCP client: read once per tick (read_available: frames, and hands each frame to the
// intake, server/host/intake.hpp), and written from the transport's flush after the handler that queued output (a tick,
// a read, a close), with one gathered write of everything waiting. Output is bounded
// (bounded_output.hpp): control messages queue up to a limit, and a snapshot waiting to be sent
// is replaced by a newer one, so a client that does not read costs at most one snapshot and a
// few small frames.
//
// The socket is out of the io_context's epoll set: nothing waits for its input (the server
// polls it once per tick), so an input arriving does not wake the server. It joins the set
// only while a write waits for room in the kernel's send buffer.
#include <sys/uio.h>

#include <array>
#include <boost/asio.hpp>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "protocol/framing.hpp"
#include "server/match/connection.hpp"
#include "server/match/match.hpp"
#include "server/net/bounded_output.hpp"

namespace arena::net {

class tcp_transport;

class session : public match::connection, public std::enable_shared_from_this<session> {
public:
    session(boost::asio::ip::tcp::socket socket, tcp_transport& owner, uint64_t id);
    ~session() override;
    session(const session&) = delete;
    session& operator=(const session&) = delete;

    void start();
    // Reads what the socket holds now into `buffer` (shared: one thread) and hands every
    // complete frame to the intake; never waits. The transport calls it once per tick.
    // `now_ns`: the host's clock when the read pass began (one reading serves every session);
    // `wall_ns`: CLOCK_REALTIME then, in ns, against which the kernel's receive times are read.
    void read_available(std::span<uint8_t> buffer, int64_t now_ns, int64_t wall_ns);
    void send(protocol::frame_bytes frame) override;
    void send_snapshot(const protocol::snapshot_encoder& snapshot, uint32_t ack_sequence) override;
    void send_snapshot_frame(std::span<const uint8_t> frame) override;
    void close(protocol::RejectCode code, std::string_view reason) override;
    // Sends Bye(reason) and closes (server shutdown, a takeover).
    void close_with_bye(std::string_view reason) override;
    void close_with_result(std::string_view reason, const protocol::match_result& result) override;
    std::string_view peer() const override { return peer_; }

    // Nanoseconds that output has waited without a byte written (0 when nothing waits).
    int64_t stalled_ns(int64_t now_ns) const { return output_.stalled_ns(now_ns); }
    uint64_t id() const { return id_; }
    bool closing() const { return closing_; }
    // Writes what waits, as far as the socket takes it now; the server calls it after the
    // handler that queued output (see request_flush), or after a tick.
    void flush();

private:
    // The match this session belongs to (the host's registry says which).
    match::match& game();
    // Frames `data` and hands each frame to the intake; false: stop reading.
    // `held_ns`: how long the bytes waited in the kernel before this read (-1: unknown).
    bool take_frames(std::span<const uint8_t> data, int64_t arrival_ns, int64_t held_ns = -1);
    // Asks the server for a flush of this session, unless one is asked for or a write waits.
    void request_flush();
    // Writes batches until the output is drained, the socket is full (then waits for room) or
    // the write fails.
    void write_pending();
    void wait_for_room();
    void close_after(protocol::frame_bytes last_frame);
    // The last word is out: ends our side and reads what the client still sends until it
    // closes too (or linger_ ends the wait), then closes.
    void half_close();
    void drain_until_closed();
    void close_now();

    // First what the tick's read pass touches (with the connection's match key and record
    // before them: the first two cache lines, which the transport fetches ahead).
    int fd_ = -1;
    bool closing_ = false;
    bool closed_ = false;
    bool flush_requested_ = false;
    bool waiting_for_room_ = false;
    tcp_transport& owner_;
    protocol::frame_reader reader_;
    boost::asio::any_io_executor executor_;
    boost::asio::ip::tcp::socket accepted_;  // until start(): then its descriptor is fd_
    uint64_t id_;
    std::string peer_;
    bounded_output output_;
    // The batch being written: the rest of take_all()'s frames, as the kernel wants them.
    std::vector<iovec> writing_;
    size_t writing_from_ = 0;  // first entry of writing_ not yet written in full
    size_t writing_bytes_ = 0;
    size_t writing_frames_ = 0;
    // fd_ in the epoll set while a write waits for room, or while a half-closed session waits
    // for the client's end (released, not closed, afterwards).
    std::optional<boost::asio::posix::stream_descriptor> room_;
    boost::asio::steady_timer linger_;  // bounds how long a closing session may flush and drain
};

}  // namespace arena::net
