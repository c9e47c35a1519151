#pragma once
// One simulated player on one TCP connection: a reader coroutine and a writer coroutine, the
// only one that writes to the socket, which sleeps on a timer used as a wake-up while its
// buffer is empty (the shape of Asio's cpp20 chat_server example). Nothing here is timed
// per bot: the fleet's one shared ticker calls on_tick() for every bot once per server tick,
// so 1000 bots cost one timer, not 1000.
#include <boost/asio/awaitable.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/steady_timer.hpp>
#include <chrono>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "client_sim/behavior.hpp"
#include "client_sim/metrics.hpp"
#include "client_sim/misbehave.hpp"
#include "client_sim/prediction.hpp"
#include "protocol/delta/receiver.hpp"
#include "protocol/framing.hpp"
#include "server/world/rng.hpp"

namespace arena::bots {

class fleet;

class bot {
public:
    using clock = std::chrono::steady_clock;

    bot(fleet& owner, std::uint32_t index, behavior_kind kind, misbehavior mode);
    bot(const bot&) = delete;
    bot& operator=(const bot&) = delete;

    // Connects, joins and plays until the session ends. Never throws: whatever goes wrong
    // ends this bot's session only, with a reason.
    boost::asio::awaitable<void> run();

    // One server tick passed: this tick's input, and a Ping once a second.
    void on_tick(std::uint64_t tick);
    // The run is over: send Bye, close once it is written.
    void finish();
    // Ends the session now, with this reason.
    void abort(const std::string& reason);
    // Gives up when no Welcome came within the join timeout.
    void check_join_timeout(clock::time_point now);

    [[nodiscard]] bool ended() const { return phase_ == phase::ended; }
    [[nodiscard]] const bot_outcome& outcome() const { return outcome_; }
    // Figures that need the whole run (this bot's snapshot rate) into the metrics.
    void add_final_figures(fleet_metrics& metrics) const;

private:
    enum class phase : std::uint8_t { idle, connecting, joining, playing, ended };
    enum class end_kind : std::uint8_t { orderly, by_server, protocol_error, socket_error };

    boost::asio::awaitable<void> reader();
    boost::asio::awaitable<void> writer();

    void handle_frame(std::span<const std::uint8_t> frame);
    void on_welcome(const protocol::Message& message);
    void on_snapshot(const protocol::Message& message);
    void on_pong(const protocol::Message& message);
    void on_reject(const protocol::Message& message);
    void on_bye(const protocol::Message& message);

    void send_input(const world::player_input& input);
    void send_ping();
    // Does this bot's fault once it is due; true when it replaces this tick's input.
    bool misbehave();
    void queue(std::span<const std::uint8_t> bytes);
    // Records the outcome (first call only) and closes the socket, which ends both coroutines.
    void end(end_kind kind, const std::string& reason);

    fleet& fleet_;
    std::uint32_t index_;
    behavior_kind kind_;
    misbehavior mode_;
    phase phase_ = phase::idle;
    bot_outcome outcome_;

    boost::asio::ip::tcp::socket socket_;
    boost::asio::steady_timer wake_;  // the writer sleeps on it; queue() cancels it
    protocol::frame_reader frames_;
    std::vector<std::uint8_t> read_buffer_;
    std::vector<std::uint8_t> pending_;  // frames waiting for the writer
    std::vector<std::uint8_t> sending_;  // frames being written; swapped with pending_
    bool close_after_flush_ = false;
    std::string close_reason_;

    // From the Welcome.
    std::uint32_t player_id_ = 0;
    std::uint32_t entity_id_ = 0;
    std::uint16_t tick_rate_ = 0;
    std::optional<predictor> predictor_;
    std::optional<behavior> behavior_;
    std::optional<protocol::delta::receiver> deltas_;  // when the bot asked for delta snapshots
    std::vector<protocol::BodyState> decoded_;         // the last delta's view as BodyState
    std::size_t message_bytes_ = 0;                    // the frame being handled, prefix included

    world::rng fault_rng_;  // garbage bytes, from the seed and index
    std::uint32_t ticks_played_ = 0;
    bool fault_done_ = false;

    clock::time_point launched_at_{};
    clock::time_point first_snapshot_at_{};
    clock::time_point last_snapshot_at_{};
    std::uint64_t snapshots_ = 0;
};

}  // namespace arena::bots
