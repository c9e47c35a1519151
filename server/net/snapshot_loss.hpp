#pragma once
// One UDP client's snapshot loss, measured from its acks, and the number of copies of each
// snapshot that loss calls for (--udp-snapshot-copies auto). A delta client acknowledges, in
// each Input (60 a second), the newest snapshot it decoded (Input.snapshot_ack); snapshots go
// 20 a second, so each one that arrives is acknowledged by about three inputs. When the ack
// moves from tick a to tick b, the snapshots sent between a and b never arrived: lost (or, far
// more rarely, all three inputs that would have acknowledged one were lost: 0.0125 % at 5 %
// loss, which errs toward a copy).
//
// The second copy goes once the smoothed loss is above 1 %. A smoothing over about 300
// snapshots (15 s at 20 Hz) needs several losses to get there: a single loss counts 0.33 %, so a
// link losing 0.2 % stays at one copy. A new client's estimate starts at the threshold, not at
// zero: nothing is known of its link yet, so its first loss brings the copies (at 5 % loss,
// after about 20 snapshots, one second) while a clean link decays to zero and never sends one.
// Starting from zero, a 5 % link would lose some 3 snapshots in 67 before its copies came,
// which alone puts more than 1 % of an 8-second session's gaps at two intervals. An ack tells
// of a loss a round trip late, so a new client's first loss on the way up counts too: while
// its first snapshots are still being measured (before its first copies, and while one lost
// snapshot would still bring them), an Input that never came (a gap in the sequences) brings
// the copies as a lost snapshot would. Inputs go 60 a second and tell at once: at 5 % loss
// the first is missed after a third of a second. While
// each snapshot goes twice, the acks say little about one datagram's loss (a snapshot is lost
// only when both copies are, p^2), so the copies go for a fixed stretch (600 snapshots, 30 s),
// extended by each snapshot lost even so; then one copy again, the estimate starting at the
// threshold, so that a link still losing more than 1 % gets its copies back at its first loss
// and one that stopped losing keeps one copy.
//
// Plain C++ (no ENet, no clock): unit-tested with a simulated link.
#include <array>
#include <cstdint>

namespace arena::net {

struct snapshot_loss_limits {
    double copy_above = 0.01;             // snapshot loss (one copy each) above which a second copy goes
    double smoothing = 1.0 / 300;         // weight of each snapshot's outcome: about the last 300 (15 s at 20 Hz)
    uint32_t copies_for_snapshots = 600;  // snapshots sent twice before the loss is measured again (30 s)
};

class snapshot_loss {
public:
    explicit snapshot_loss(snapshot_loss_limits limits = {}) : limits_(limits), snapshot_loss_(limits.copy_above) {}

    // A snapshot of `tick` went to the client (its first copy); ticks increase.
    void sent(uint32_t tick);
    // An Input's snapshot_ack: the newest snapshot tick the client decoded (0: none yet).
    void acked(uint32_t tick);
    // An Input's sequence (one Input a datagram over UDP; sequences rise by one per input).
    void input_arrived(uint32_t sequence);

    // The estimated loss of one datagram, 0 to 1 (while two copies go: as it was when they started).
    [[nodiscard]] double datagram_loss() const { return snapshot_loss_; }
    // How many times each snapshot should go now: 1 or 2.
    [[nodiscard]] uint32_t copies() const { return copies_; }
    // Snapshots whose fate is known (acknowledged, or skipped by a newer ack).
    [[nodiscard]] uint64_t samples() const { return samples_; }

private:
    void record(bool lost);
    void start_copies();

    snapshot_loss_limits limits_;
    // The ticks of the last snapshots sent, oldest overwritten: 64 cover 3 s at 20 Hz, longer
    // than any ack takes to come back in a game.
    std::array<uint32_t, 64> sent_{};
    uint64_t sent_count_ = 0;
    uint32_t last_ack_ = 0;
    double snapshot_loss_;  // smoothed: the fraction of snapshots sent once that did not arrive
    uint64_t samples_ = 0;
    uint32_t copies_ = 1;
    uint32_t twice_left_ = 0;  // while copies_ is 2: snapshots still to send twice
    uint32_t last_input_ = 0;  // the newest Input sequence seen
    bool had_copies_ = false;  // a first stretch of copies began: the acks alone decide from then on
};

}  // namespace arena::net
