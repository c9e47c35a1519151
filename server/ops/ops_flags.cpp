#include "server/ops/ops_flags.hpp"

#include <boost/asio/ip/address.hpp>
#include <charconv>
#include <cstring>

namespace arena::ops {

void add_ops_flags(CLI::App& app, ops_options& options) {
    app.add_option_function<uint16_t>(
           "--metrics-port", [&options](uint16_t port) { options.metrics_port = port; },
           "serve /metrics and /healthz over HTTP on this port, at the --metrics-bind address (default: off; 0 "
           "picks a free one)")
        ->type_name("PORT");
    app.add_option("--metrics-bind", options.metrics_bind,
                   "the address /metrics and /healthz listen on, e.g. a private one while --bind is 0.0.0.0 "
                   "(default: the --bind address)")
        ->type_name("ADDR")
        ->check(CLI::Validator(
            [](std::string& text) {
                boost::system::error_code ec;
                boost::asio::ip::make_address(text, ec);
                return ec ? "not an IP address: '" + text + "'" : std::string();
            },
            "IP address"));
    app.add_flag("--serve-recording", options.serve_recording,
                 "serve the --record file at /recording (for the replay page; it shows every body's position, "
                 "a map of the match): on the --metrics-port address while the match runs, on --http-port only "
                 "once it is over; honours a single Range (default: off, /recording is a 404)");
    app.add_flag(
        "--agones", options.agones,
        "talk to the Agones SDK sidecar: ready, health pings, shutdown (default: on when AGONES_SDK_HTTP_PORT is set)");
    app.add_option_function<uint16_t>(
           "--agones-port",
           [&options](uint16_t port) {
               options.agones_sdk.port = port;
               options.agones_port_given = true;
           },
           "the sidecar's REST port on localhost (default: $AGONES_SDK_HTTP_PORT, else 9358)")
        ->type_name("PORT")
        ->check(CLI::Range(1, 65535));
    app.add_option_function<double>(
           "--agones-shutdown-timeout",
           [&options](double s) { options.agones_sdk.shutdown_timeout_ns = static_cast<int64_t>(s * 1e9); },
           "seconds to wait for the sidecar to accept /shutdown before exiting anyway (default 5)")
        ->check(CLI::PositiveNumber);
}

std::string apply_agones_environment(ops_options& options, const char* sdk_http_port) {
    if (!sdk_http_port || !*sdk_http_port) return "";
    unsigned port = 0;
    const char* end = sdk_http_port + std::strlen(sdk_http_port);
    const auto r = std::from_chars(sdk_http_port, end, port);
    if (r.ec != std::errc{} || r.ptr != end || port == 0 || port > 65535)
        return std::string("AGONES_SDK_HTTP_PORT: not a port number: '") + sdk_http_port + "'";
    options.agones = true;
    if (!options.agones_port_given) options.agones_sdk.port = static_cast<uint16_t>(port);
    return "";
}

}  // namespace arena::ops
