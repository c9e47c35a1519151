#include "ws_client.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/websocket.hpp>

#include "server_process.hpp"

namespace arena::test {

namespace beast = boost::beast;
namespace websocket = beast::websocket;
using boost::asio::ip::tcp;

struct ws_client::impl {
    boost::asio::io_context io;
    websocket::stream<tcp::socket> ws{io};
    bool open = false;
    bool ended = false;
    int status = 0;
    bool reading = false;  // a read is outstanding (it survives a timeout to the next call)
    bool read_done = false;
    boost::system::error_code read_ec;
    beast::flat_buffer buffer;

    // Runs the io_context until `done` or the timeout.
    template <class Done>
    void run(std::chrono::milliseconds timeout, Done done) {
        const auto deadline = std::chrono::steady_clock::now() + timeout;
        while (!done() && std::chrono::steady_clock::now() < deadline) {
            io.restart();
            io.run_for(std::chrono::milliseconds(5));
        }
    }
};

ws_client::ws_client(uint16_t port, const std::string& origin, const std::string& target, int receive_buffer,
                     const std::string& from)
    : impl_(std::make_unique<impl>()) {
    boost::system::error_code ec;
    if (receive_buffer > 0 || !from.empty()) impl_->ws.next_layer().open(tcp::v4(), ec);
    if (receive_buffer > 0)  // before connecting, when TCP negotiates its window
        impl_->ws.next_layer().set_option(boost::asio::socket_base::receive_buffer_size(receive_buffer), ec);
    if (!from.empty()) {
        impl_->ws.next_layer().bind(tcp::endpoint(boost::asio::ip::make_address(from), 0), ec);
        if (ec) return;
    }
    impl_->ws.next_layer().connect(tcp::endpoint(boost::asio::ip::make_address("127.0.0.1"), port), ec);
    if (ec) return;
    impl_->ws.set_option(websocket::stream_base::decorator([origin](websocket::request_type& request) {
        if (!origin.empty()) request.set(beast::http::field::origin, origin);
    }));
    websocket::response_type response;
    bool done = false;
    impl_->ws.async_handshake(response, "127.0.0.1:" + std::to_string(port), target, [&](boost::system::error_code e) {
        ec = e;
        done = true;
    });
    impl_->run(std::chrono::milliseconds(3000), [&] { return done; });
    impl_->status = static_cast<int>(response.result_int());
    impl_->open = done && !ec;
    if (impl_->open) impl_->ws.binary(true);
}

ws_client::~ws_client() {
    boost::system::error_code ec;
    impl_->ws.next_layer().close(ec);
}

bool ws_client::open() const {
    return impl_->open;
}

int ws_client::refused_status() const {
    return impl_->open ? 0 : impl_->status;
}

bool ws_client::send_binary(const std::vector<uint8_t>& bytes) {
    boost::system::error_code ec;
    impl_->ws.binary(true);
    impl_->ws.write(boost::asio::buffer(bytes), ec);
    return !ec;
}

bool ws_client::send_text(const std::string& text) {
    boost::system::error_code ec;
    impl_->ws.text(true);
    impl_->ws.write(boost::asio::buffer(text), ec);
    impl_->ws.binary(true);
    return !ec;
}

bool ws_client::send_fragmented(const std::vector<uint8_t>& bytes, size_t piece) {
    boost::system::error_code ec;
    impl_->ws.binary(true);
    for (size_t at = 0; at < bytes.size() && !ec; at += piece) {
        const size_t n = std::min(piece, bytes.size() - at);
        impl_->ws.write_some(at + n == bytes.size(), boost::asio::buffer(bytes.data() + at, n), ec);
    }
    return !ec;
}

bool ws_client::ping() {
    boost::system::error_code ec;
    impl_->ws.ping({}, ec);
    return !ec;
}

std::optional<std::vector<uint8_t>> ws_client::read_message(std::chrono::milliseconds timeout) {
    if (!impl_->open || impl_->ended) return std::nullopt;
    if (!impl_->reading) {
        impl_->reading = true;
        impl_->read_done = false;
        impl_->buffer.clear();
        impl_->ws.async_read(impl_->buffer, [this](boost::system::error_code ec, size_t) {
            impl_->read_ec = ec;
            impl_->read_done = true;
        });
    }
    impl_->run(timeout, [&] { return impl_->read_done; });
    if (!impl_->read_done) return std::nullopt;
    impl_->reading = false;
    if (impl_->read_ec) {
        impl_->ended = true;
        return std::nullopt;
    }
    const auto data = impl_->buffer.data();
    const auto* p = static_cast<const uint8_t*>(data.data());
    return std::vector<uint8_t>(p, p + data.size());
}

std::optional<std::vector<uint8_t>> ws_client::read_until(protocol::Payload type, std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < deadline) {
        auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
        auto m = read_message(std::max(left, std::chrono::milliseconds(1)));
        if (!m) {
            if (impl_->ended) return std::nullopt;
            continue;
        }
        const protocol::Message* message = message_of(*m);
        if (message != nullptr && message->payload_type() == type) return m;
    }
    return std::nullopt;
}

bool ws_client::closed_by_peer(std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (!impl_->ended && std::chrono::steady_clock::now() < deadline) {
        auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
        read_message(std::max(left, std::chrono::milliseconds(1)));
    }
    return impl_->ended || !impl_->open;
}

int ws_client::close_code() const {
    return static_cast<int>(impl_->ws.reason().code);
}

std::string raw_http(uint16_t port, const std::string& request, std::chrono::milliseconds timeout,
                     const std::string& from) {
    const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
    if (!from.empty()) {
        sockaddr_in local{};
        local.sin_family = AF_INET;
        if (::inet_pton(AF_INET, from.c_str(), &local.sin_addr) != 1 ||
            ::bind(fd, reinterpret_cast<sockaddr*>(&local), sizeof local) != 0) {
            ::close(fd);
            return "";
        }
    }
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(port);
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    std::string answer;
    if (::connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0 &&
        ::send(fd, request.data(), request.size(), MSG_NOSIGNAL) == static_cast<ssize_t>(request.size())) {
        const auto deadline = std::chrono::steady_clock::now() + timeout;
        while (std::chrono::steady_clock::now() < deadline) {
            pollfd p{fd, POLLIN, 0};
            if (::poll(&p, 1, 20) <= 0) continue;
            char chunk[4096];
            const ssize_t n = ::recv(fd, chunk, sizeof chunk, 0);
            if (n <= 0) break;
            answer.append(chunk, static_cast<size_t>(n));
        }
    }
    ::close(fd);
    return answer;
}

}  // namespace arena::test
