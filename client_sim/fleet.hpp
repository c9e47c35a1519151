#pragma once
// All the bots of one run, on one io_context and one thread: launches them at the connect
// rate, drives every bot's input from one shared timer at the server's tick rate, prints a
// progress line each second and ends the run after --duration (or on SIGINT/SIGTERM). The
// figures, the shared encoder and the parsed Welcome config are client_shared's.
#include <boost/asio/awaitable.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/signal_set.hpp>
#include <boost/asio/steady_timer.hpp>
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "client_sim/bot.hpp"
#include "client_sim/bot_session.hpp"
#include "client_sim/client_shared.hpp"
#include "client_sim/metrics.hpp"
#include "client_sim/options.hpp"
#include "client_sim/report.hpp"
#include "protocol/messages.hpp"

namespace arena::bots {

class fleet : public client_shared {
public:
    using clock = std::chrono::steady_clock;

    fleet(boost::asio::io_context& io, options opts);
    fleet(const fleet&) = delete;
    fleet& operator=(const fleet&) = delete;
    ~fleet() override;

    // The whole run; completes once every bot's session has ended.
    boost::asio::awaitable<void> run();
    // After run(): the figures and the exit code.
    final_report report();

    // --- for the bots --------------------------------------------------------------------
    boost::asio::io_context& io() { return io_; }
    const options& opts() const { return opts_; }
    const boost::asio::ip::tcp::endpoint& endpoint() const { return endpoint_; }
    // Nanoseconds since the run started: the time the bots' cores are given.
    time_ns now_ns() const;
    void count_in(std::size_t bytes);
    void count_out(std::size_t bytes);
    // The first Welcome gives the tick rate and starts the shared ticker.
    void on_joined(const protocol::welcome_info& welcome) override;

private:
    boost::asio::awaitable<void> launch();
    boost::asio::awaitable<void> ticker();
    // A progress line a second until the run's end, then the goodbyes.
    boost::asio::awaitable<void> report_loop();
    boost::asio::awaitable<void> wind_down();
    void roll_interval(clock::time_point now, double interval_s);
    void watch_signals();
    void stop();

    boost::asio::io_context& io_;
    options opts_;
    std::vector<std::unique_ptr<bot_session>> bots_;  // TCP or UDP, as --transport says
    boost::asio::ip::tcp::endpoint endpoint_;
    boost::asio::steady_timer tick_timer_;
    boost::asio::steady_timer launch_timer_;
    boost::asio::steady_timer report_timer_;
    boost::asio::signal_set signals_;

    clock::time_point start_{};
    clock::time_point end_{};
    bool all_launched_ = false;
    std::uint32_t launched_ = 0;
    std::uint16_t tick_rate_ = 0;  // 0 until the first Welcome
};

}  // namespace arena::bots
