#include "server/server_run.hpp"

#include <csignal>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <system_error>

#include "protocol/snapshot.hpp"
#include "server/host/host.hpp"
#include "server/host/log.hpp"
#include "server/replay/recorder.hpp"

namespace arena {

namespace {

// --record: every tick goes to the file as the match runs; finished when the match ends or the
// server shuts down. A FILE records the default match; a folder (one that exists, or a path
// ending in '/') records every match, each to FOLDER/ID.arpl. A write that fails is logged once
// and that match goes on unrecorded.
class match_recordings {
public:
    // False: the file (or the default match's, in a folder) cannot be opened (said on stderr).
    bool open(host::process_host& host, const cli::server_setup& setup) {
        setup_ = &setup;
        folder_ = cli::record_is_folder(setup.record);
        if (folder_) {
            std::error_code made;
            std::filesystem::create_directories(setup.record, made);
            if (made) {
                std::fprintf(stderr, "arena-server: --record: cannot create the folder %s: %s\n", setup.record.c_str(),
                             made.message().c_str());
                return false;
            }
        }
        // Called for the matches there now (the default one) and for every match started later:
        // it must capture nothing of this call's. The default match's file must open, or the
        // server does not start.
        host.matches().observe(
            [this](host::hosted_match& m) {
                if (m.key == 0 || folder_) start(m);
            },
            [this](host::hosted_match& m, const std::string&) { finish(m.key, *m.game); });
        if (!recordings_.contains(0)) return false;
        host.on_shutdown = [this, &host] {
            for (const auto& [key, m] : host.matches().matches()) finish(key, *m.game);
        };
        return true;
    }

private:
    struct one {
        std::optional<replay::recorder> recorder;
        std::string path;
        bool failed = false;
    };

    // Opens m's recording and records its ticks; one that cannot be opened is said (on stderr
    // for the default match, in the log for another) and that match plays unrecorded.
    void start(host::hosted_match& m) {
        const std::string path =
            folder_ ? (std::filesystem::path(setup_->record) / (m.id + ".arpl")).string() : setup_->record;
        match::match& game = *m.game;
        const match::match_config& c = game.config();
        auto opened = replay::recorder::open(
            path, replay::make_header(game.state(), c.preset, c.seed, c.tick_rate, setup_->hash_interval));
        if (!opened) {
            if (m.key == 0) {
                std::fprintf(stderr, "arena-server: --record: %s\n", opened.error.c_str());
            } else {
                host::log_line("match=%s is not recorded: %s", m.id.c_str(), opened.error.c_str());
            }
            return;
        }
        one& r = recordings_[m.key];
        r.recorder.emplace(std::move(opened.value));
        r.path = path;
        game.on_tick = [&r, id = m.id](const match::tick_record& t, uint64_t hash) {
            if (r.failed) return;
            if (auto s = r.recorder->record_tick(t, hash); !s) {
                host::log_line("recording of match %s failed, it goes on unrecorded: %s", id.c_str(), s.error.c_str());
                r.failed = true;
            }
        };
    }

    void finish(uint64_t key, match::match& game) {
        auto it = recordings_.find(key);
        if (it == recordings_.end()) return;
        one& r = it->second;
        game.on_tick = nullptr;
        if (!r.failed) {
            // The state hash (the world's, then the rules'), as every recorded tick's.
            const world::world& w = game.state();
            if (auto s = r.recorder->finish(w.tick(), rules::state_hash(w, game.game_rules())); !s)
                host::log_line("recording failed at the end: %s", s.error.c_str());
            else
                host::log_line("recorded %u ticks to %s", w.tick(), r.path.c_str());
        }
        recordings_.erase(it);
    }

    const cli::server_setup* setup_ = nullptr;
    bool folder_ = false;
    std::map<uint64_t, one> recordings_;  // by match key
};

}  // namespace

int run_server(const cli::server_setup& setup) {
    host::process_host host(setup.host, setup.ops);
    match_recordings recording;  // outlives the host's run: its callbacks point here
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
