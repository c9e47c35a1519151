#pragma once
// Everything an operator talks to, behind one object the server's main wires in: the
// /metrics + /healthz endpoint and the Agones sidecar client. The server stays unaware of
// both: it hands over a function that snapshots its figures and one that says whether its
// tick loop advances.
#include <boost/asio.hpp>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "server/ops/agones.hpp"
#include "server/ops/http_server.hpp"
#include "server/ops/metrics.hpp"

namespace arena::ops {

struct ops_options {
    std::string bind = "127.0.0.1";        // the game's --bind
    std::string metrics_bind;              // --metrics-bind: the endpoint's own address; "" = bind
    std::optional<uint16_t> metrics_port;  // unset: no HTTP endpoint; 0: any free port
    bool agones = false;                   // talk to the Agones SDK sidecar
    agones_options agones_sdk{};
    bool agones_port_given = false;  // --agones-port: AGONES_SDK_HTTP_PORT does not override it
    bool serve_recording = false;    // --serve-recording: /recording on the metrics port
    std::string recording;           // the --record file ("" when none)
};

class ops_service {
public:
    ops_service(boost::asio::io_context& io, ops_options options, std::function<server_metrics()> metrics,
                std::function<bool()> healthy, log_fn log = {});

    // Call once the game port listens: binds the metrics port (throws boost::system::system_error when
    // it cannot) and tells Agones the server is ready.
    void start_after_listening();
    // The match is over (end of --duration, SIGTERM, ...): tells Agones and calls `done` on
    // the io thread once it accepted or gave up; without Agones, `done` is simply posted.
    void on_match_end(std::function<void()> done);

    // High density on Agones (density_sync.hpp); nothing without Agones. Call
    // keep_density() before start_after_listening(): `on_allocation` creates the match an
    // allocation names and then calls want_density(). want_density(): the matches and players
    // now (cheap to call often: only a change is sent).
    void keep_density(std::function<void(const allocation_request&)> on_allocation);
    void want_density(density_state desired);
    bool keeps_density() const { return options_.agones && static_cast<bool>(on_allocation_); }

    // The /metrics body now, process figures included.
    std::string metrics_text() const;
    // The address the endpoint listens on: --metrics-bind, else --bind.
    const std::string& metrics_address() const {
        return options_.metrics_bind.empty() ? options_.bind : options_.metrics_bind;
    }
    // The bound metrics port (0 when the endpoint is off).
    uint16_t metrics_port() const { return http_ ? http_->port() : 0; }
    const ops_options& options() const { return options_; }

private:
    boost::asio::io_context& io_;
    ops_options options_;
    std::function<server_metrics()> metrics_;
    std::function<bool()> healthy_;
    log_fn log_;
    std::unique_ptr<http_server> http_;
    std::unique_ptr<agones_client> agones_;
    std::function<void(const allocation_request&)> on_allocation_;
    std::optional<density_state> density_;  // the last wanted, for an Agones client made later
};

}  // namespace arena::ops
