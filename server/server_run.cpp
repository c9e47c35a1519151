#include "server/server_run.hpp"

#include <csignal>
#include <cstdio>
#include <memory>
#include <optional>

#include "protocol/snapshot.hpp"
#include "server/host/host.hpp"
#include "server/host/log.hpp"
#include "server/replay/recorder.hpp"

namespace arena {

namespace {

// --record: every tick goes to the file as the match runs; finished at shutdown. A write that
// fails is logged once and the match goes on unrecorded.
class match_recording {
public:
    // False: the file cannot be opened (said on stderr).
    bool open(host::process_host& host, const cli::server_setup& setup) {
        match::match& game = host.default_match();
        const world::world& w = game.state();
        const match::match_config& m = setup.host.match;
        auto opened = replay::recorder::open(
            setup.record, replay::make_header(w, m.preset, m.seed, m.tick_rate, setup.hash_interval));
        if (!opened) {
            std::fprintf(stderr, "arena-server: --record: %s\n", opened.error.c_str());
            return false;
        }
        recorder_.emplace(std::move(opened.value));
        game.on_tick = [this](const match::tick_record& r, uint64_t hash) {
            if (auto s = recorder_->record_tick(r, hash); !s && !failed_) {
                host::log_line("recording failed, the session goes on unrecorded: %s", s.error.c_str());
                failed_ = true;
            }
        };
        host.on_shutdown = [this, &game, path = setup.record] {
            if (failed_) return;
            // The state hash (the world's, then the rules'), as every recorded tick's.
            const world::world& w = game.state();
            const uint64_t end_hash = rules::state_hash(w, game.game_rules());
            if (auto s = recorder_->finish(w.tick(), end_hash); !s)
                host::log_line("recording failed at the end: %s", s.error.c_str());
            else
                host::log_line("recorded %u ticks to %s", w.tick(), path.c_str());
        };
        return true;
    }

private:
    std::optional<replay::recorder> recorder_;
    bool failed_ = false;
};

}  // namespace

int run_server(const cli::server_setup& setup) {
    host::process_host host(setup.host, setup.ops);
    match_recording recording;  // outlives the host's run: its callbacks point here
    if (!setup.record.empty() && !recording.open(host, setup)) return 2;
    // Started in this order: "listening on", then "udp listening on", then "http listening on".
    host.add(std::make_unique<net::tcp_transport>(host, setup.tcp));
    if (setup.udp) host.add(std::make_unique<net::udp_transport>(host, *setup.udp));
    if (setup.web) host.add(std::make_unique<net::web_transport>(host, *setup.web, host.http_handlers()));
    host.start();
    host.run();
    // The match is over and the process on its way out (stats, the recording, the exit): a
    // repeated signal (a supervisor's second SIGTERM) must not end it now with the signal's
    // status, as it could once the host's signal handling is gone. Blocked, it stays pending.
    sigset_t late;
    sigemptyset(&late);
    for (const int signo : {SIGINT, SIGTERM, SIGHUP, SIGUSR1}) sigaddset(&late, signo);
    pthread_sigmask(SIG_BLOCK, &late, nullptr);
    host::log_line("stopped after %u ticks", host.current_tick());
    if (const uint64_t n = protocol::non_finite_values_replaced(); n > 0)  // protocol/snapshot.hpp
        host::log_line("error: the world diverged: %llu non-finite values were sent as 0 (check the world config)",
                       static_cast<unsigned long long>(n));
    return 0;
}

}  // namespace arena
