#pragma once
// The little HTTP/1.1 the ops endpoints need, as pure functions over text: parse a request's
// head, route it, format a response, read a response's status. Bytes from a peer never
// throw: a bad head is a status code to answer with.
#include <functional>
#include <string>
#include <string_view>
#include <variant>

namespace arena::ops {

struct http_request {
    std::string method;  // "GET"
    std::string path;    // "/metrics", without the query string
};

struct http_error {
    int status;          // 400, 405, 505...
    std::string reason;  // for the body and the log
};

// head: the request line and headers, up to and including the blank line ("\r\n\r\n").
std::variant<http_request, http_error> parse_request_head(std::string_view head);

struct http_response {
    int status = 200;
    std::string content_type = "text/plain; charset=utf-8";
    std::string body;
};

// What the ops endpoint serves. Called on the server's io thread.
struct http_handlers {
    std::function<std::string()> metrics_text;  // the /metrics body
    std::function<bool()> healthy;              // /healthz: true while the tick loop advances
};

// GET /metrics, GET /healthz, 404 for any other path, 405 for any other method.
http_response route(const http_request& request, const http_handlers& handlers);

// Status line, Content-Type, Content-Length, Connection: close, blank line, body.
std::string format_response(const http_response& response);
std::string format_error(const http_error& error);

// The status code of "HTTP/1.x NNN ...", or 0 when the text does not start like that.
int parse_response_status(std::string_view response);

// "HTTP/1.1 POST" request with a JSON body, for the Agones sidecar.
std::string format_post(std::string_view host, uint16_t port, std::string_view path, std::string_view json_body);

}  // namespace arena::ops
