// arena-healthcheck: GET a URL on loopback and exit 0 on HTTP 200, 1 otherwise, 2 on a usage
// error. The runtime image has no curl and should not grow one (and its libcurl and TLS stack)
// for a probe of our own endpoint: Docker's HEALTHCHECK runs this instead.
//   arena-healthcheck [http://127.0.0.1:8080/healthz] [--timeout SECONDS]
#include <boost/asio.hpp>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "server/cli/bounds.hpp"
#include "server/cli_helpers.hpp"
#include "server/ops/http_client.hpp"

namespace {

struct target {
    std::string host;
    uint16_t port = 0;
    std::string path;
};

// Only what the probe needs: http://IPV4:PORT/PATH.
bool parse_url(const std::string& url, target& out) {
    const std::string scheme = "http://";
    if (url.rfind(scheme, 0) != 0) return false;
    const size_t host_end = url.find(':', scheme.size());
    if (host_end == std::string::npos) return false;
    const size_t slash = url.find('/', host_end);
    out.host = url.substr(scheme.size(), host_end - scheme.size());
    const std::string port =
        url.substr(host_end + 1, slash == std::string::npos ? std::string::npos : slash - host_end - 1);
    out.path = slash == std::string::npos ? "/" : url.substr(slash);
    char* end = nullptr;
    const long p = std::strtol(port.c_str(), &end, 10);
    if (port.empty() || *end || p < 1 || p > 65535) return false;
    out.port = static_cast<uint16_t>(p);
    return true;
}

// A coroutine with no result of its own, spawned detached: g++ 12 with the sanitizers warns
// falsely (-Wmismatched-new-delete) about co_spawn with a completion handler inlined into main.
boost::asio::awaitable<void> get_into(arena::ops::http_result& result, target t, int64_t timeout_ns) {
    const auto executor = co_await boost::asio::this_coro::executor;
    result = co_await arena::ops::http_get(executor, t.host, t.port, t.path, timeout_ns);
}

int probe(const target& t, double timeout_s) {
    boost::system::error_code ec;
    boost::asio::ip::make_address_v4(t.host, ec);
    if (ec) {
        std::fprintf(stderr, "arena-healthcheck: not an IPv4 address: %s\n", t.host.c_str());
        return 1;
    }
    boost::asio::io_context io(1);
    arena::ops::http_result result;
    boost::asio::co_spawn(io, get_into(result, t, static_cast<int64_t>(timeout_s * 1e9)), boost::asio::detached);
    io.run();
    std::printf("%s:%u%s -> %d\n", t.host.c_str(), t.port, t.path.c_str(), result.status);
    return result.status == 200 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"arena-healthcheck: exit 0 when the URL answers HTTP 200 within the timeout, 1 otherwise",
                 "arena-healthcheck"};
    std::string url = "http://127.0.0.1:8080/healthz";
    double timeout_s = 2;
    app.add_option("url", url, "http://IPV4:PORT/PATH to GET")->capture_default_str();
    app.add_option("--timeout", timeout_s, "seconds for the whole exchange")->capture_default_str();
    arena::cli::bound_option(app, "--timeout", {0, 3600, true, "s"});
    if (int code = arena::cli::parse_or_exit_code(app, argc, argv); code >= 0) return code;
    target t;
    if (!parse_url(url, t)) {
        std::fprintf(stderr, "arena-healthcheck: expected http://IPV4:PORT/PATH, got '%s'\n", url.c_str());
        return 2;
    }
    return probe(t, timeout_s);
}
