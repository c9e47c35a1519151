#pragma once
// What the host and a transport know of each other, and nothing more. A transport (TCP, UDP,
// WebSocket: server/net/) turns sockets into match::connections and bytes into frames for the
// intake (intake.hpp); the host (host.hpp) owns the io_context, the tick loop, the signals and
// the shutdown. The host knows a transport only as a `transport`, and a transport knows the
// host only as a `transport_host`: no transport includes another's header or the host's class.
// Everything runs on the host's one io_context thread.
#include <algorithm>
#include <boost/asio/io_context.hpp>
#include <cstddef>
#include <cstdint>

#include "server/host/host_options.hpp"
#include "server/host/intake.hpp"
#include "server/host/lobby.hpp"
#include "server/host/match_registry.hpp"
#include "server/ops/process_counters.hpp"

namespace arena::host {

// The host as a transport sees it.
class transport_host {
public:
    virtual boost::asio::io_context& io() = 0;
    virtual const host_options& options() const = 0;
    // Every frame a client sends goes through the intake; its connection's match is the registry's.
    virtual host::intake& intake() = 0;
    virtual match_registry& matches() = 0;
    // A request to the lobby (GET and POST /matches), with the server's token rules.
    virtual lobby_answer lobby(const lobby_request& request) = 0;
    // The process's counters: bytes and messages out, UDP's own figures.
    virtual ops::process_counters& counters() = 0;
    // The steady clock, ns: arrival times, stalls, timeouts.
    virtual int64_t now_ns() const = 0;
    virtual bool shutting_down() const = 0;
    // A client connection opened (the peak) or closed (a shutdown may be waiting for the last).
    virtual void connection_opened() = 0;
    virtual void connection_closed() = 0;

    // One tick, ns.
    int64_t tick_ns() const { return 1'000'000'000LL / std::max<int64_t>(1, options().match.tick_rate); }
    void count_out(size_t bytes, size_t messages = 1) {
        counters().bytes_out += bytes;
        counters().messages_out += messages;
    }

protected:
    ~transport_host() = default;
};

// A transport as the host sees it.
class transport {
public:
    virtual ~transport() = default;

    // Binds the host's --bind address, prints its "... listening on HOST:PORT" line, and takes
    // clients. Throws when it cannot bind.
    virtual void start() = 0;
    // The host shuts down: take no new connections (the match says Bye to the open ones).
    virtual void stop() {}
    // Before the due ticks: what clients sent since the last tick goes to the intake (a
    // transport that reads as bytes arrive has nothing to do).
    virtual void read_before_tick() {}
    // After the ticks: write what they queued, so that a tick's sends do not lengthen it.
    virtual void flush_after_tick() {}
    // About every 250 ms of the tick loop: drop the clients whose output has not moved for
    // the stall timeout.
    virtual void check_stalls(int64_t /*now_ns*/) {}
    // Client connections open now (connections_open and its peak count every transport's).
    virtual uint64_t open_connections() const = 0;
    // Whether a shutdown waits for these connections to send their Bye and close (stream
    // transports); UDP's last words go out with ENet's own disconnect instead.
    virtual bool drains_at_shutdown() const { return true; }
};

}  // namespace arena::host
