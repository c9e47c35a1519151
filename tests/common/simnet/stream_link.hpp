#pragma once
// One direction of a simulated stream (TCP's semantics as the application sees them): bytes
// arrive in order, exactly once. Each write is one or more segments; a lost segment is resent
// after the retransmission timeout (doubling at each loss of the same segment) and holds back
// every byte behind it until it arrives: head-of-line blocking. Duplicated or reordered
// segments change nothing the reader sees (TCP's receiver discards and reorders them), only
// when: a segment is readable once it and every segment before it have arrived.
//
// Not modelled: congestion control (the window shrinking after a loss), fast retransmit, and
// bandwidth; a test that needs them adds them here.
#include <cstdint>
#include <deque>
#include <optional>
#include <span>
#include <vector>

#include "simnet/conditions.hpp"
#include "simnet/link_stats.hpp"

namespace arena::simnet {

class stream_link {
public:
    stream_link(const conditions& c, std::uint64_t seed);

    // Bytes into the stream (nothing after close()).
    void write(std::span<const std::uint8_t> bytes, sim_time now);
    // The writer closes: the reader sees the end once every byte written before it is read.
    void close(sim_time now);

    // When the next bytes (or the end) become readable; nothing when nothing is in flight.
    [[nodiscard]] std::optional<sim_time> next_due() const;
    // Appends to `out` every byte readable by `now`; returns how many.
    std::size_t read(sim_time now, std::vector<std::uint8_t>& out);
    // True once, the first time it is asked after every byte was read and the close arrived
    // by `now`: the reader's end of file.
    bool take_end(sim_time now);
    [[nodiscard]] bool closed() const { return closed_; }

    [[nodiscard]] const link_stats& stats() const { return stats_; }

private:
    // When one segment sent now arrives, its losses and resends included.
    sim_time arrival(sim_time now);

    struct segment {
        sim_time readable = 0;  // it and every segment before it have arrived
        std::vector<std::uint8_t> bytes;
    };
    conditions conditions_;
    dice dice_;
    std::deque<segment> segments_;  // readable times never decrease
    sim_time last_readable_ = 0;
    bool closed_ = false;
    std::optional<sim_time> end_readable_;  // when the close arrives; reset once taken
    link_stats stats_;
};

}  // namespace arena::simnet
