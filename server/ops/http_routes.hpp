#pragma once
// What the ops endpoint answers, as a pure function of the method and path: GET /metrics,
// GET /healthz (HEAD as GET: the transport sends no body), 404 for any other path, 405 for any
// other method. No HTTP parsing here (Beast
// does that in http_server.cpp), so the rules can be tested without a socket.
#include <functional>
#include <string>

namespace arena::ops {

struct http_request {
    std::string method;  // "GET"
    std::string path;    // "/metrics", without the query string
};

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

http_response route(const http_request& request, const http_handlers& handlers);

}  // namespace arena::ops
