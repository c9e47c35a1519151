#include "simnet/match_sim.hpp"

#include <algorithm>

#include "protocol/verify.hpp"

namespace arena::simnet {

struct match_sim::sim_client {
    sim_client(bots::client_shared& shared, bots::client_params params, link_kind kind, const sim_options& o,
               std::uint64_t index)
        : core(std::make_unique<bots::client_core>(shared, std::move(params))),
          up(kind, o.up, link_seed(o.seed, 2 * index)),
          down(kind, o.down, link_seed(o.seed, 2 * index + 1)) {}

    std::unique_ptr<bots::client_core> core;
    path up;
    path down;
    std::unique_ptr<server_end> server;
    sim_time launch_at = 0;
    bool launched = false;
    sim_time phase = 0;  // ns: this client's ticks fall this long after the match's
    std::uint64_t tick = 0;
    sim_time next_tick = 0;
    sim_time wake = 0;                // the earliest of its next tick (or launch) and its paths' next arrivals
    protocol::frame_reader splitter;  // the core's output cut into frames, for datagrams
};

match_sim::match_sim(const match::match_config& config, const world::world_config& world, const sim_options& options)
    : matches_(host::one_match(config, world)), options_(options) {
    dice phases(link_seed(options.seed, ~0ULL));
    const sim_time period = 1'000'000'000ULL / config.tick_rate;
    for (std::uint32_t i = 0; i < options.clients; ++i) {
        bots::client_params p;
        p.index = i;
        p.kind = bots::resolve_behavior(options.behavior, i);
        if (options.misbehave != bots::misbehavior::none &&
            bots::is_misbehaving(i, options.clients, options.misbehave_share))
            p.mode = options.misbehave;
        p.seed = options.seed;
        p.name = "sim-" + std::to_string(i);
        p.delta_snapshots = options.delta_snapshots;
        p.unordered = options.kind == link_kind::datagram;
        auto c = std::make_unique<sim_client>(shared_, std::move(p), options.kind, options, i);
        c->server = std::make_unique<server_end>(intake_, c->down, now_, "sim-" + std::to_string(i));
        c->launch_at = i * options.launch_spacing;
        c->phase = phases.upto(period - 1);
        c->next_tick = c->phase + period;
        refresh(*c);
        clients_.push_back(std::move(c));
    }
}

match_sim::~match_sim() = default;

const bots::client_core& match_sim::client(std::size_t i) const {
    return *clients_[i]->core;
}
server_end& match_sim::server(std::size_t i) {
    return *clients_[i]->server;
}
const path& match_sim::up(std::size_t i) const {
    return clients_[i]->up;
}
void match_sim::cut_off(std::size_t i, sim_time duration) {
    clients_[i]->up.block(now_, now_ + duration);
    clients_[i]->down.block(now_, now_ + duration);
}

const path& match_sim::down(std::size_t i) const {
    return clients_[i]->down;
}

sim_time match_sim::server_tick_time(std::uint64_t tick) const {
    return tick * 1'000'000'000ULL / matches_.default_match().config().tick_rate;
}

void match_sim::flush(sim_client& c) {
    bots::client_core& core = *c.core;
    std::vector<std::uint8_t>& out = core.output();
    if (!out.empty()) {
        if (c.up.kind() == link_kind::stream) {
            c.up.send(out, true, now_);
        } else {
            // One datagram per frame; the control messages go reliably.
            std::span<const std::uint8_t> rest = out;
            while (!rest.empty()) {
                rest = rest.subspan(c.splitter.feed(rest));
                if (!c.splitter.has_frame()) break;  // a well-behaved core queues whole frames
                const auto m = protocol::verify_message(c.splitter.frame(), protocol::client_frame_limits);
                const bool reliable = m && (m.value->payload_type() == protocol::Payload::Hello ||
                                            m.value->payload_type() == protocol::Payload::Bye);
                c.up.send(c.splitter.frame(), reliable, now_);
                c.splitter.next();
            }
        }
        out.clear();
    }
    if (core.closing() && !core.ended()) core.flushed();
    if (core.ended() && !c.up.closed()) c.up.close(now_);
}

void match_sim::refresh(sim_client& c) {
    c.wake = c.launched ? c.next_tick : c.launch_at;
    if (const auto due = c.up.next_due()) c.wake = std::min(c.wake, *due);
    if (const auto due = c.down.next_due()) c.wake = std::min(c.wake, *due);
}

void match_sim::step(sim_time horizon) {
    const sim_time period = 1'000'000'000ULL / matches_.default_match().config().tick_rate;
    sim_time next = std::min(horizon, server_tick_time(ticks_ + 1));
    for (const auto& c : clients_) next = std::min(next, c->wake);
    now_ = std::max(now_, next);

    // Only the clients with something due now: the others' paths and ticks lie ahead.
    for (const auto& c : clients_) {
        if (c->wake > now_) continue;
        bots::client_core& core = *c->core;
        const bool datagrams = c->down.kind() == link_kind::datagram;
        c->down.deliver(
            now_,
            [&](std::span<const std::uint8_t> data) {
                if (datagrams) {
                    core.on_frame(data, now_);
                } else {
                    core.on_bytes(data, now_);
                }
            },
            [&] { core.on_transport_end(bots::client_core::end_kind::by_server, "server closed the connection"); });
        flush(*c);
        server_end& s = *c->server;
        c->up.deliver(
            now_, [&](std::span<const std::uint8_t> data) { s.on_data(data); }, [&] { s.on_end(); });
        if (!c->launched && c->launch_at <= now_) {
            c->launched = true;
            c->server->open();
            core.launch(now_);
            core.connected();
            flush(*c);
        }
    }
    const bool match_ticks = now_ == server_tick_time(ticks_ + 1);
    if (match_ticks) {
        matches_.tick_all([] { return int64_t{0}; });
        ++ticks_;
    }
    for (const auto& c : clients_) {
        if (c->wake > now_ && !match_ticks) continue;
        if (c->launched && c->next_tick <= now_) {
            c->core->on_tick(++c->tick, now_);
            c->core->check_join_timeout(now_);
            flush(*c);
            c->next_tick += period;
        }
        // The match's tick may have sent to anyone; otherwise the server answers on the path of
        // the client whose message it handled (a takeover's Bye to another connection waits
        // for the next tick to be seen here: at most one tick late).
        refresh(*c);
    }
}

void match_sim::run_ticks(std::uint64_t ticks) {
    const std::uint64_t target = ticks_ + ticks;
    while (ticks_ < target) step(server_tick_time(target));
}

bool match_sim::finish(sim_time limit) {
    shared_.set_stopping();
    for (const auto& c : clients_) {
        c->core->finish();
        flush(*c);
        refresh(*c);
    }
    const sim_time until = now_ + limit;
    const auto all_closed = [&] {
        return std::all_of(clients_.begin(), clients_.end(), [](const auto& c) {
            return c->core->ended() && c->server->closed() && !c->up.next_due() && !c->down.next_due();
        });
    };
    while (!all_closed() && now_ < until) step(until);
    return all_closed();
}

}  // namespace arena::simnet
