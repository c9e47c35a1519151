#pragma once
// A TCP test client that has joined arena-server, and the reads the end-to-end tests over TCP
// share (server_tests.cpp, server_limits_tests.cpp).
#include <catch2/catch.hpp>
#include <chrono>
#include <string>

#include "protocol/decode.hpp"
#include "protocol/version.hpp"
#include "server_process.hpp"

namespace arena::test {

struct joined_client {
    test_client client;
    protocol::welcome_info welcome;
    explicit joined_client(uint16_t port, const std::string& name = "tester", int receive_buffer = 0)
        : client(port, receive_buffer) {
        client.send_frame(protocol::encode_hello(protocol::protocol_version, name, ""));
        auto frame = client.read_until(protocol::Payload::Welcome);
        REQUIRE(frame);
        auto w = protocol::decode_welcome(*message_of(*frame));
        REQUIRE(w);
        welcome = w.value;
    }
};

inline protocol::reject_msg expect_reject(test_client& c) {
    auto frame = c.read_until(protocol::Payload::Reject);
    REQUIRE(frame);
    auto r = protocol::decode_reject(*message_of(*frame));
    REQUIRE(r);
    CHECK(c.closed_by_peer());
    return r.value;
}

// Snapshots a client receives in `duration` while it reads everything.
inline int count_snapshots(test_client& c, std::chrono::milliseconds duration) {
    int count = 0;
    const auto end = std::chrono::steady_clock::now() + duration;
    while (std::chrono::steady_clock::now() < end) {
        auto frame = c.read_frame(std::chrono::milliseconds(20));
        if (frame && message_of(*frame) && message_of(*frame)->payload_type() == protocol::Payload::Snapshot) ++count;
    }
    return count;
}

}  // namespace arena::test
