#include "server/ops/http_routes.hpp"

#include "server/ops/metrics.hpp"

namespace arena::ops {

http_response route(const http_request& request, const http_handlers& handlers) {
    const bool known = request.path == "/metrics" || request.path == "/healthz";
    if (!known) return {404, "text/plain; charset=utf-8", "not found\n"};
    // HEAD is GET without the body (the transport leaves it out): a load balancer's probe.
    if (request.method != "GET" && request.method != "HEAD")
        return {405, "text/plain; charset=utf-8", "only GET and HEAD\n"};
    if (request.path == "/healthz") {
        // No handler means nobody can vouch for the tick loop: say so rather than guess.
        const bool ok = handlers.healthy && handlers.healthy();
        return ok ? http_response{200, "text/plain; charset=utf-8", "ok\n"}
                  : http_response{503, "text/plain; charset=utf-8", "tick loop stalled\n"};
    }
    if (!handlers.metrics_text) return {503, "text/plain; charset=utf-8", "no metrics\n"};
    return {200, metrics_content_type, handlers.metrics_text()};
}

}  // namespace arena::ops
