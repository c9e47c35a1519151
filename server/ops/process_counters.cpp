#include "server/ops/process_counters.hpp"

namespace arena::ops {

void report(const process_counters& c, match::figure_sink& out) {
    out.gauge({"", "", "", "tick_ms_p50"}, c.window.tick_ms_p50);
    out.gauge({"", "", "", "tick_ms_p99"}, c.window.tick_ms_p99);
    out.gauge({"", "", "", "tick_ms_max"}, c.window.tick_ms_max);
    out.counter(
        {"overruns", "arena_tick_overruns_total", "Ticks dropped because the tick loop fell behind.", "overruns"},
        c.tick_overruns);
    out.gauge({"", "", "", "bytes_in_per_s", 0}, c.window.bytes_in_per_s);
    out.gauge({"", "", "", "bytes_out_per_s", 0}, c.window.bytes_out_per_s);
    out.gauge({"", "arena_connections_open", "Open client connections, joined or not.", "connections"},
              c.connections_open);
    out.gauge({"connections_peak", "arena_connections_peak", "Most client connections open at once."},
              c.connections_peak);
    out.counter({"bytes_in", "arena_received_bytes_total", "Bytes read from clients."}, c.bytes_in);
    out.counter({"bytes_out", "arena_sent_bytes_total", "Bytes written to clients."}, c.bytes_out);
    out.counter({"messages_in", "arena_received_messages_total", "Protocol messages read from clients."},
                c.messages_in);
    out.counter({"messages_out", "arena_sent_messages_total", "Protocol messages written to clients."}, c.messages_out);
    out.counter({"snapshots_fragmented", "arena_snapshots_fragmented_total",
                 "UDP snapshots larger than a datagram, sent as ENet fragments (BodyState views)."},
                c.snapshots_fragmented);
    out.counter({"snapshot_copies", "arena_snapshot_copies_total",
                 "UDP snapshot datagrams sent again, a tick after the first (--udp-snapshot-copies)."},
                c.snapshot_copies);
    out.counters_by({"udp_refused", "arena_udp_refused_datagrams_total",
                     "UDP datagrams refused before ENet read them, by reason: shape (not a connect, or "
                     "too short to answer), rate (an address's connects over its rate), peer_limit (no "
                     "free peer slot), connect_key (a connect without the server's UDP connect key, with "
                     "--token-secret), half_open (a connect from an address holding 2 half-open handshakes), "
                     "before_hello (a fragment or a held command from a peer before its Hello), fragment (a "
                     "fragment claiming more fragments or bytes than its length allows)."},
                    "reason", c.udp_refused);
}

}  // namespace arena::ops
