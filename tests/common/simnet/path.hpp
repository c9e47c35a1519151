#pragma once
// One direction of a simulated connection, over either kind of link, as a transport uses it:
// frames in, bytes (a stream) or frames (datagrams) out. On datagrams a frame goes reliably
// (control messages: Hello, Welcome, Reject, Bye) or not (Input, Ping, Snapshot), and the end
// of the connection is an empty reliable message, since UDP itself has no end.
#include <cstdint>
#include <optional>
#include <span>
#include <variant>
#include <vector>

#include "simnet/datagram_link.hpp"
#include "simnet/stream_link.hpp"

namespace arena::simnet {

enum class link_kind : std::uint8_t { stream, datagram };

class path {
public:
    path(link_kind kind, const conditions& c, std::uint64_t seed);

    [[nodiscard]] link_kind kind() const { return kind_; }
    // One whole frame. `reliable` matters on datagrams only: a stream is reliable anyway.
    void send(std::span<const std::uint8_t> frame, bool reliable, sim_time now);
    // The sender closes; nothing is sent after.
    void close(sim_time now);
    [[nodiscard]] bool closed() const { return closed_; }

    [[nodiscard]] std::optional<sim_time> next_due() const;
    // Hands what arrived by `now` to `data` (a stream's bytes, or one datagram each call),
    // then the end, once, to `end`. Nothing arrives after the end.
    template <typename Data, typename End>
    void deliver(sim_time now, Data&& data, End&& end);

    [[nodiscard]] const link_stats& stats() const;
    // Datagrams only: see datagram_link::block.
    void block(sim_time from, sim_time until) {
        if (auto* d = std::get_if<datagram_link>(&link_)) d->block(from, until);
    }

private:
    link_kind kind_;
    std::variant<stream_link, datagram_link> link_;
    bool closed_ = false;
    bool ended_ = false;  // the receiver saw the end
    std::vector<std::uint8_t> buffer_;
};

template <typename Data, typename End>
void path::deliver(sim_time now, Data&& data, End&& end) {
    if (auto* s = std::get_if<stream_link>(&link_)) {
        buffer_.clear();
        if (s->read(now, buffer_) > 0 && !ended_) data(std::span<const std::uint8_t>(buffer_));
        if (s->take_end(now) && !ended_) {
            ended_ = true;
            end();
        }
        return;
    }
    auto& d = std::get<datagram_link>(link_);
    while (d.receive(now, buffer_)) {
        if (ended_) continue;  // late datagrams after the end: nobody listens
        if (buffer_.empty()) {
            ended_ = true;
            end();
        } else {
            data(std::span<const std::uint8_t>(buffer_));
        }
    }
}

}  // namespace arena::simnet
