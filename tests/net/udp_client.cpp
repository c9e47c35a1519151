#include "udp_client.hpp"

#include <arpa/inet.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <stdexcept>
#include <string>

#include "server_process.hpp"

namespace arena::test {

udp_client::udp_client(uint16_t port, std::chrono::milliseconds timeout, enet_uint32 connect_data) {
    enet_initialize();
    host_ = enet_host_create(nullptr, 1, 2, 0, 0);
    if (host_ == nullptr) throw std::runtime_error("enet_host_create failed");
    ENetAddress address{};
    enet_address_set_host_ip(&address, "127.0.0.1");
    address.port = port;
    peer_ = enet_host_connect(host_, &address, 2, connect_data);
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (!connected_ && !disconnected_ && std::chrono::steady_clock::now() < deadline) service_once(10);
}

udp_client::~udp_client() {
    if (peer_ != nullptr && connected_ && !disconnected_) enet_peer_reset(peer_);
    enet_host_destroy(host_);
}

bool udp_client::service_once(int timeout_ms) {
    ENetEvent event{};
    const int got = enet_host_service(host_, &event, static_cast<enet_uint32>(timeout_ms));
    if (got <= 0) return false;
    switch (event.type) {
        case ENET_EVENT_TYPE_CONNECT:
            connected_ = true;
            break;
        case ENET_EVENT_TYPE_DISCONNECT:
            disconnected_ = true;
            break;
        case ENET_EVENT_TYPE_RECEIVE:
            received_.emplace_back(event.packet->data, event.packet->data + event.packet->dataLength);
            enet_packet_destroy(event.packet);
            break;
        case ENET_EVENT_TYPE_NONE:
            break;
    }
    return true;
}

void udp_client::send_reliable(std::span<const uint8_t> frame) {
    enet_peer_send(peer_, 0, enet_packet_create(frame.data(), frame.size(), ENET_PACKET_FLAG_RELIABLE));
    enet_host_flush(host_);
}

void udp_client::send_unreliable(std::span<const uint8_t> frame) {
    enet_peer_send(peer_, 1, enet_packet_create(frame.data(), frame.size(), ENET_PACKET_FLAG_UNSEQUENCED));
    enet_host_flush(host_);
}

void udp_client::pump(std::chrono::milliseconds duration) {
    const auto deadline = std::chrono::steady_clock::now() + duration;
    while (std::chrono::steady_clock::now() < deadline) service_once(1);
}

std::optional<std::vector<uint8_t>> udp_client::read_frame(std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (received_.empty() && !disconnected_ && std::chrono::steady_clock::now() < deadline) service_once(1);
    if (received_.empty()) return std::nullopt;
    std::vector<uint8_t> frame = std::move(received_.front());
    received_.erase(received_.begin());
    return frame;
}

std::optional<std::vector<uint8_t>> udp_client::read_until(protocol::Payload type, std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < deadline) {
        auto frame = read_frame(
            std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now()));
        if (!frame) return std::nullopt;
        const protocol::Message* message = message_of(*frame);
        if (message != nullptr && message->payload_type() == type) return frame;
    }
    return std::nullopt;
}

void send_raw_datagram(uint16_t port, std::span<const uint8_t> bytes) {
    const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
    if (fd < 0) return;
    sockaddr_in to{};
    to.sin_family = AF_INET;
    to.sin_port = htons(port);
    to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    ::sendto(fd, bytes.data(), bytes.size(), 0, reinterpret_cast<const sockaddr*>(&to), sizeof to);
    ::close(fd);
}

raw_udp_socket::raw_udp_socket(uint16_t port, const char* source) {
    fd_ = ::socket(AF_INET, SOCK_DGRAM, 0);
    if (fd_ < 0) throw std::runtime_error("socket failed");
    sockaddr_in from{};
    from.sin_family = AF_INET;
    if (::inet_pton(AF_INET, source, &from.sin_addr) != 1 ||
        ::bind(fd_, reinterpret_cast<const sockaddr*>(&from), sizeof from) != 0) {
        ::close(fd_);
        throw std::runtime_error(std::string("cannot bind a UDP socket to ") + source);
    }
    sockaddr_in to{};
    to.sin_family = AF_INET;
    to.sin_port = htons(port);
    to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    // Connected: send() goes to the server and only its datagrams are received.
    if (::connect(fd_, reinterpret_cast<const sockaddr*>(&to), sizeof to) != 0) {
        ::close(fd_);
        throw std::runtime_error("connect failed");
    }
}

raw_udp_socket::~raw_udp_socket() {
    ::close(fd_);
}

void raw_udp_socket::send(std::span<const uint8_t> bytes) {
    ::send(fd_, bytes.data(), bytes.size(), 0);
}

std::optional<std::vector<uint8_t>> raw_udp_socket::receive(std::chrono::milliseconds timeout) {
    pollfd readable{fd_, POLLIN, 0};
    if (::poll(&readable, 1, static_cast<int>(timeout.count())) <= 0) return std::nullopt;
    std::vector<uint8_t> datagram(65536);
    const ssize_t got = ::recv(fd_, datagram.data(), datagram.size(), 0);
    if (got < 0) return std::nullopt;
    datagram.resize(static_cast<size_t>(got));
    return datagram;
}

}  // namespace arena::test
