#include "server/ops/http_message.hpp"

#include "server/ops/metrics.hpp"

namespace arena::ops {

namespace {

const char* status_text(int status) {
    switch (status) {
        case 200:
            return "OK";
        case 400:
            return "Bad Request";
        case 404:
            return "Not Found";
        case 405:
            return "Method Not Allowed";
        case 408:
            return "Request Timeout";
        case 431:
            return "Request Header Fields Too Large";
        case 500:
            return "Internal Server Error";
        case 503:
            return "Service Unavailable";
        case 505:
            return "HTTP Version Not Supported";
        default:
            return "Unknown";
    }
}

bool is_token_char(char c) {
    return c > 32 && c < 127;
}

}  // namespace

std::variant<http_request, http_error> parse_request_head(std::string_view head) {
    const size_t line_end = head.find("\r\n");
    if (line_end == std::string_view::npos) return http_error{400, "no request line"};
    const std::string_view line = head.substr(0, line_end);
    // "METHOD SP TARGET SP HTTP/1.x": exactly two single spaces, as RFC 9112 asks.
    const size_t first = line.find(' ');
    const size_t second = first == std::string_view::npos ? first : line.find(' ', first + 1);
    if (second == std::string_view::npos || line.find(' ', second + 1) != std::string_view::npos)
        return http_error{400, "malformed request line"};
    const std::string_view method = line.substr(0, first);
    const std::string_view target = line.substr(first + 1, second - first - 1);
    const std::string_view version = line.substr(second + 1);
    if (method.empty() || target.empty() || target.front() != '/') return http_error{400, "malformed request line"};
    for (char c : method)
        if (c < 'A' || c > 'Z') return http_error{400, "malformed method"};
    for (char c : target)
        if (!is_token_char(c)) return http_error{400, "malformed target"};
    if (version != "HTTP/1.1" && version != "HTTP/1.0") return http_error{505, "only HTTP/1.0 and HTTP/1.1"};
    return http_request{std::string(method), std::string(target.substr(0, target.find('?')))};
}

http_response route(const http_request& request, const http_handlers& handlers) {
    const bool known = request.path == "/metrics" || request.path == "/healthz";
    if (!known) return {404, "text/plain; charset=utf-8", "not found\n"};
    if (request.method != "GET") return {405, "text/plain; charset=utf-8", "only GET\n"};
    if (request.path == "/healthz") {
        // No handler means nobody can vouch for the tick loop: say so rather than guess.
        const bool ok = handlers.healthy && handlers.healthy();
        return ok ? http_response{200, "text/plain; charset=utf-8", "ok\n"}
                  : http_response{503, "text/plain; charset=utf-8", "tick loop stalled\n"};
    }
    if (!handlers.metrics_text) return {503, "text/plain; charset=utf-8", "no metrics\n"};
    return {200, metrics_content_type, handlers.metrics_text()};
}

std::string format_response(const http_response& response) {
    // Appends only: g++ 12 at -O3 warns falsely (-Wrestrict, GCC bug 105329) on
    // "literal" + std::string chains.
    std::string out;
    out.reserve(160 + response.body.size());
    out.append("HTTP/1.1 ").append(std::to_string(response.status)).append(" ").append(status_text(response.status));
    out.append("\r\nContent-Type: ").append(response.content_type);
    out.append("\r\nContent-Length: ").append(std::to_string(response.body.size()));
    if (response.status == 405) out.append("\r\nAllow: GET");
    out.append("\r\nCache-Control: no-store\r\nConnection: close\r\n\r\n");
    out.append(response.body);
    return out;
}

std::string format_error(const http_error& error) {
    std::string body = error.reason;
    body += '\n';
    return format_response({error.status, "text/plain; charset=utf-8", std::move(body)});
}

int parse_response_status(std::string_view response) {
    if (response.size() < 12 || response.substr(0, 7) != "HTTP/1." || response[8] != ' ') return 0;
    int status = 0;
    for (size_t i = 9; i < 12; ++i) {
        if (response[i] < '0' || response[i] > '9') return 0;
        status = status * 10 + (response[i] - '0');
    }
    return status;
}

std::string format_post(std::string_view host, uint16_t port, std::string_view path, std::string_view json_body) {
    std::string out;
    out.append("POST ")
        .append(path)
        .append(" HTTP/1.1\r\nHost: ")
        .append(host)
        .append(":")
        .append(std::to_string(port));
    out.append("\r\nContent-Type: application/json\r\nContent-Length: ").append(std::to_string(json_body.size()));
    out.append("\r\nConnection: close\r\n\r\n").append(json_body);
    return out;
}

}  // namespace arena::ops
