#include "server/ops/ops_service.hpp"

namespace arena::ops {

ops_service::ops_service(boost::asio::io_context& io, ops_options options, std::function<server_metrics()> metrics,
                         std::function<bool()> healthy, log_fn log)
    : io_(io),
      options_(std::move(options)),
      metrics_(std::move(metrics)),
      healthy_(std::move(healthy)),
      log_(std::move(log)) {}

std::string ops_service::metrics_text() const {
    server_metrics m = metrics_ ? metrics_() : server_metrics{};
    m.process = read_process_stats();
    return render_metrics(m);
}

void ops_service::start_after_listening() {
    if (options_.metrics_port && !http_) {
        http_server_options http_options;
        http_options.bind = metrics_address();
        http_options.port = *options_.metrics_port;
        if (options_.serve_recording) http_options.recording = options_.recording;
        http_ = std::make_unique<http_server>(io_, http_options,
                                              http_handlers{[this] { return metrics_text(); }, healthy_}, log_);
        http_->start();
        if (log_) log_("metrics on http://" + metrics_address() + ":" + std::to_string(http_->port()) + "/metrics");
    }
    if (options_.agones && !agones_) {
        agones_ = std::make_unique<agones_client>(io_, options_.agones_sdk, healthy_, log_);
        if (on_allocation_) {
            agones_->keep_density(on_allocation_);
            if (density_) agones_->want_density(*density_);
        }
        if (log_)
            log_("agones: sidecar at " + options_.agones_sdk.host + ":" + std::to_string(options_.agones_sdk.port));
        agones_->start();
    }
}

void ops_service::keep_density(std::function<void(const allocation_request&)> on_allocation) {
    on_allocation_ = std::move(on_allocation);
}

void ops_service::want_density(density_state desired) {
    if (!options_.agones) return;
    if (agones_) agones_->want_density(desired);
    density_ = std::move(desired);
}

void ops_service::on_match_end(std::function<void()> done) {
    // /healthz keeps answering (503 once the tick loop stops) until the process exits.
    if (agones_) {
        agones_->shutdown(std::move(done));
        return;
    }
    if (options_.agones) {
        // Agones was asked for but start_after_listening() never ran: still say goodbye.
        agones_ = std::make_unique<agones_client>(io_, options_.agones_sdk, healthy_, log_);
        agones_->shutdown(std::move(done));
        return;
    }
    if (done) boost::asio::post(io_, std::move(done));
}

}  // namespace arena::ops
