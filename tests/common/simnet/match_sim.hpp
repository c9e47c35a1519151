#pragma once
// A match and N client cores in one process, joined by simulated links, in virtual time: no
// sockets, no sleeping, the same run for the same seed. The clock jumps from one event to the
// next (a delivery, a server tick, a client tick), so 6000 ticks of 64 clients take seconds.
//
// Each client is a bots::client_core, as arena-bots runs over TCP, with its own tick phase;
// the server's end of each connection is a server_end handing frames to the match. Within one
// instant: deliveries first (client by client, in index order), then the match's tick, then
// the clients' ticks.
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "client_sim/client_core.hpp"
#include "server/match/match.hpp"
#include "simnet/path.hpp"
#include "simnet/server_end.hpp"

namespace arena::simnet {

struct sim_options {
    link_kind kind = link_kind::stream;
    conditions up;    // client → server
    conditions down;  // server → client
    std::uint64_t seed = 1;
    std::uint32_t clients = 8;
    bots::behavior_choice behavior = bots::behavior_choice::mixed;
    bool delta_snapshots = true;
    sim_time launch_spacing = 5 * ms;  // client i connects at i × this
    // A fault for a share of the clients, chosen as arena-bots chooses them (misbehave.hpp).
    bots::misbehavior misbehave = bots::misbehavior::none;
    double misbehave_share = 0.1;
};

class match_sim {
public:
    match_sim(const arena::match::match_config& config, const world::world_config& world, const sim_options& options);
    match_sim(const match_sim&) = delete;
    match_sim& operator=(const match_sim&) = delete;
    ~match_sim();

    // Runs until the match has made `ticks` more ticks.
    void run_ticks(std::uint64_t ticks);
    // Every client says Bye. Runs until every connection is closed at both ends, or `limit`
    // more virtual time passed; true when all closed.
    bool finish(sim_time limit = 30'000 * ms);

    [[nodiscard]] arena::match::match& match() { return matches_.default_match(); }
    // Every match of the simulated process (Hello.mode and Hello.match create and join others).
    [[nodiscard]] host::match_registry& matches() { return matches_; }
    [[nodiscard]] sim_time now() const { return now_; }
    [[nodiscard]] std::uint64_t ticks() const { return ticks_; }
    [[nodiscard]] std::size_t size() const { return clients_.size(); }
    [[nodiscard]] const bots::client_core& client(std::size_t i) const;
    [[nodiscard]] server_end& server(std::size_t i);
    [[nodiscard]] const path& up(std::size_t i) const;
    [[nodiscard]] const path& down(std::size_t i) const;
    // Datagrams: client i loses everything it sends and is sent from now for `duration`.
    void cut_off(std::size_t i, sim_time duration);
    [[nodiscard]] bots::client_shared& shared() { return shared_; }

private:
    struct sim_client;
    void step(sim_time horizon);
    void flush(sim_client& c);
    void refresh(sim_client& c);
    [[nodiscard]] sim_time server_tick_time(std::uint64_t tick) const;

    // The process's side of the server ends: their frames come in as a transport's do.
    ops::process_counters counters_;
    host::match_registry matches_;
    host::intake intake_{matches_, counters_};
    sim_options options_;
    bots::client_shared shared_;
    std::vector<std::unique_ptr<sim_client>> clients_;
    sim_time now_ = 0;
    std::uint64_t ticks_ = 0;
};

}  // namespace arena::simnet
