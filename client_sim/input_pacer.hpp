#pragma once
// Keeps a client's inputs from waiting on the server longer than they must (protocol/README.md,
// "Input pacing"). The world takes one input per tick. When an input comes late (its datagram
// was lost and it rode in the next one, or a TCP segment was resent), the server repeats the
// previous one for that tick, and from then on every input of this client waits a tick longer:
// nothing else ever takes that tick back, so over a session under loss the waits add up to the
// input buffer's size. Each delta snapshot says how many of this client's inputs wait beyond
// the first (Snapshot.extra_inputs_waiting); when two snapshots in a row say some do, the
// client leaves one tick's input out, and the server's queue is one shorter.
//
// One waiting input is kept on purpose: it is what lets a lost input arrive a tick late
// without the world repeating its predecessor (a repeat moves the server's ship a step away
// from the client's prediction). Leaving a tick out costs nothing the server sees: the inputs
// still run in sequence, one per tick, each as predicted.
#include <cstdint>

namespace arena::bots {

class input_pacer {
public:
    // Snapshots in a row that must show extra inputs waiting: one could be a burst that the
    // next tick clears.
    static constexpr int settle_snapshots = 2;

    // A snapshot's ack_sequence and extra_inputs_waiting.
    void on_snapshot(std::uint32_t ack_sequence, std::uint16_t extra_inputs_waiting);
    // At each tick, before its input: false when this tick's input is to be left out.
    // `next_sequence` is the sequence the input would carry.
    bool send_this_tick(std::uint32_t next_sequence);
    [[nodiscard]] std::uint64_t left_out() const { return left_out_; }

private:
    int seen_ = 0;                   // snapshots in a row with extra inputs waiting
    bool leave_out_ = false;         // the next tick's input
    std::uint32_t counts_from_ = 0;  // snapshots acknowledging less were taken before the last gap
    std::uint64_t left_out_ = 0;
};

}  // namespace arena::bots
