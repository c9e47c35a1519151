#pragma once
// One simulated player over UDP (ENet): the second I/O adapter around a client_core. Each bot
// has its own ENet host (its own source port), watched by Asio; Hello, Ping and Bye go on the
// reliable ordered channel, Input unsequenced on the datagram channel, and every datagram the
// server sends is one frame for client_core::on_frame (client_params::unordered).
//
// --simulate-latency and --simulate-jitter delay each message on the bot's side, both ways:
// latency ± a uniform jitter, so unreliable messages may overtake each other; reliable ones
// keep their order (ENet delivers them in order, and so does the delay).
#include <enet/enet.h>

#include <boost/asio/awaitable.hpp>
#include <boost/asio/posix/stream_descriptor.hpp>
#include <boost/asio/steady_timer.hpp>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "client_sim/bot_session.hpp"
#include "server/world/rng.hpp"

namespace arena::bots {

class fleet;

struct simulated_delay {
    double latency_ms = 0;  // added one way, each direction
    double jitter_ms = 0;   // ± uniform around the latency
};

class udp_bot : public bot_session {
public:
    udp_bot(fleet& owner, client_params params, simulated_delay delay);
    ~udp_bot() override;

    boost::asio::awaitable<void> run() override;

private:
    struct delayed {
        std::vector<std::uint8_t> frame;
        bool reliable = false;
    };
    boost::asio::awaitable<void> watch_socket();
    boost::asio::awaitable<void> pump();
    // ENet's events, without waiting.
    void service();
    // Moves the core's output into ENet (through the delay line), closes when the core says.
    void sync() override;
    void send_now(const delayed& d);
    void deliver_due(time_ns now);
    time_ns delay_ns(bool reliable, time_ns& last_reliable);
    void close_transport();

    fleet& fleet_;
    simulated_delay delay_;
    world::rng jitter_rng_;
    ENetHost* host_ = nullptr;
    ENetPeer* peer_ = nullptr;
    bool connected_ = false;
    bool closed_ = false;
    boost::asio::posix::stream_descriptor readable_;
    boost::asio::steady_timer timer_;
    // The delay lines, by due time (ties keep their order).
    std::multimap<time_ns, delayed> outgoing_;
    std::multimap<time_ns, std::vector<std::uint8_t>> incoming_;
    time_ns last_reliable_out_ = 0;
    time_ns last_in_ = 0;
};

}  // namespace arena::bots
