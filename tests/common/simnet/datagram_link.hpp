#pragma once
// One direction of a simulated datagram path (UDP's semantics): each message is lost,
// delayed by latency ± jitter, sometimes duplicated (the copy arrives later) or held back so
// that later messages overtake it, and arrives whole or not at all. The shape of netcode's and
// yojimbo's network simulators, on a virtual clock: the link is told the time, never reads one.
//
// send_reliable() models what a reliable-ordered channel over the datagrams (acks and resends,
// as yojimbo's channels do) gives the application, without modelling its packets: a lost
// transmission is resent after the retransmission timeout, and the message arrives exactly
// once, after every reliable message sent before it.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "simnet/conditions.hpp"
#include "simnet/link_stats.hpp"

namespace arena::simnet {

class datagram_link {
public:
    datagram_link(const conditions& c, std::uint64_t seed);

    void send(std::span<const std::uint8_t> message, sim_time now);
    void send_reliable(std::span<const std::uint8_t> message, sim_time now);

    // When the next message arrives; nothing when none is in flight.
    [[nodiscard]] std::optional<sim_time> next_due() const;
    // Moves the next message that arrived by `now` into `out`, in arrival order (equal times:
    // in the order sent). False when none has.
    bool receive(sim_time now, std::vector<std::uint8_t>& out);

    // Every transmission sent in [from, until) is lost: a reliable message gets through with
    // the first resend after it. For a test of a client cut off for a while.
    void block(sim_time from, sim_time until) {
        block_from_ = from;
        block_until_ = until;
    }

    [[nodiscard]] const link_stats& stats() const { return stats_; }
    [[nodiscard]] std::size_t in_flight() const { return flight_.size(); }

private:
    struct in_flight_message {
        sim_time arrives = 0;
        std::uint64_t order = 0;  // tie-break: the order sent
        std::vector<std::uint8_t> bytes;
    };
    struct later {
        bool operator()(const in_flight_message& a, const in_flight_message& b) const {
            return a.arrives != b.arrives ? a.arrives > b.arrives : a.order > b.order;
        }
    };
    void put(std::span<const std::uint8_t> message, sim_time arrives);

    conditions conditions_;
    dice dice_;
    std::vector<in_flight_message> flight_;  // a heap: front() arrives first
    std::uint64_t next_order_ = 0;
    sim_time last_reliable_ = 0;  // when the last reliable message arrives
    sim_time block_from_ = 0;
    sim_time block_until_ = 0;
    [[nodiscard]] bool blocked(sim_time now) const { return now >= block_from_ && now < block_until_; }
    link_stats stats_;
};

}  // namespace arena::simnet
