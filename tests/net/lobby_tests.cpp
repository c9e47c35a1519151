// The lobby on arena-server's HTTP port (server/host/lobby.*, docs/MATCHES.md) end to end:
// list, create (listed and private), join the created match by its id over the WebSocket,
// the refusals: unknown mode, bad body, too large a body, a wrong method, no room; and one
// address that creates and leaves matches starving no other.
#include <catch2/catch.hpp>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <thread>

#include "protocol/decode.hpp"
#include "protocol/version.hpp"
#include "server/config/modes.hpp"
#include "server_process.hpp"
#include "ws_client.hpp"

using namespace arena;
using namespace arena::test;
using namespace std::chrono_literals;
using nlohmann::json;

namespace {

std::string post(uint16_t port, const std::string& path, const std::string& body) {
    return raw_http(port, "POST " + path +
                              " HTTP/1.1\r\nHost: x\r\nContent-Type: application/json\r\nContent-Length: " +
                              std::to_string(body.size()) + "\r\n\r\n" + body);
}

std::string body_of(const std::string& answer) {
    const size_t at = answer.find("\r\n\r\n");
    return at == std::string::npos ? std::string() : answer.substr(at + 4);
}

int status_of(const std::string& answer) {
    return answer.size() > 12 ? std::stoi(answer.substr(9, 3)) : 0;
}

json get_json(uint16_t port, const std::string& path) {
    const std::string answer = raw_http(port, "GET " + path + " HTTP/1.1\r\nHost: x\r\n\r\n");
    REQUIRE(status_of(answer) == 200);
    return json::parse(body_of(answer));
}

std::string modes_file() {
    const std::string path = temp_path("modes.json");
    std::ofstream(path) << R"({"modes": [{"name": "duel", "preset": "asteroids", "max_players": 2}]})";
    return path;
}

}  // namespace

TEST_CASE("the lobby lists, creates and describes matches, and a client joins one by its id", "[net][ws][lobby]") {
    http_server s({"--modes", modes_file(), "--max-matches", "3"});
    const json modes = get_json(s.http_port, "/modes");
    REQUIRE(modes.size() == config::builtin_modes().size() + 1);  // the built-in ones (a game each), then duel
    const json& duel_mode = modes.back();
    CHECK(duel_mode["name"] == "duel");
    CHECK(duel_mode["capacity"] == 2);
    CHECK(duel_mode["rules"] == "asteroids");
    CHECK(modes[0]["rules"] == "sandbox");
    const json first = get_json(s.http_port, "/matches");
    REQUIRE(first.size() == 1);
    CHECK(first[0]["id"] == "default");
    CHECK(first[0]["mode"] == "asteroids");

    const std::string listed = post(s.http_port, "/matches", R"({"mode": "duel"})");
    REQUIRE(status_of(listed) == 201);
    const json duel = json::parse(body_of(listed));
    CHECK(duel["mode"] == "duel");
    CHECK(duel["capacity"] == 2);
    CHECK(duel["state"] == "open");
    const std::string hidden = post(s.http_port, "/matches", R"({"mode": "duel", "private": true})");
    REQUIRE(status_of(hidden) == 201);
    const std::string secret_id = json::parse(body_of(hidden))["id"];

    const json now = get_json(s.http_port, "/matches");
    CHECK(now.size() == 2);  // the private match is not listed
    for (const json& m : now) CHECK(m["id"] != secret_id);
    CHECK(get_json(s.http_port, "/matches/" + secret_id)["private"] == true);

    // Joined by its id, as an invitation is.
    ws_client c(s.http_port);
    REQUIRE(c.open());
    protocol::hello_msg hello{protocol::protocol_version, "friend", "", true, false, secret_id, ""};
    REQUIRE(c.send_binary(protocol::encode_hello(hello)));
    const auto frame = c.read_until(protocol::Payload::Welcome, 3000ms);
    REQUIRE(frame);
    const auto welcome = protocol::decode_welcome(*message_of(*frame));
    REQUIRE(welcome);
    CHECK(welcome.value.match == secret_id);
    CHECK(welcome.value.mode == "duel");
    CHECK(get_json(s.http_port, "/matches/" + secret_id)["players"] == 1);

    // Three matches is this server's limit: a fourth is refused, and says why.
    const std::string full = post(s.http_port, "/matches", R"({"mode": "duel"})");
    CHECK(status_of(full) == 503);
    CHECK(body_of(full).find("as many matches as it may (3)") != std::string::npos);
}

TEST_CASE("the lobby refuses what it cannot take with a status and one line", "[net][ws][lobby]") {
    http_server s({"--modes", modes_file()});
    CHECK(status_of(post(s.http_port, "/matches", R"({"mode": "chess"})")) == 404);
    CHECK(status_of(post(s.http_port, "/matches", "not json")) == 400);
    CHECK(status_of(post(s.http_port, "/matches", R"({"mode": "duel", "rounds": 3})")) == 400);
    CHECK(status_of(post(s.http_port, "/matches", R"({"mode": 7})")) == 400);
    CHECK(status_of(post(s.http_port, "/matches", std::string(5000, ' '))) == 400);  // over 4096 bytes
    CHECK(status_of(post(s.http_port, "/healthz", "{}")) == 400);                    // only the lobby takes a body
    CHECK(status_of(raw_http(s.http_port, "DELETE /matches HTTP/1.1\r\nHost: x\r\n\r\n")) == 405);
    CHECK(status_of(raw_http(s.http_port, "GET /matches/0123456789abcdef HTTP/1.1\r\nHost: x\r\n\r\n")) == 404);
    // Still serving.
    CHECK(status_of(raw_http(s.http_port, "GET /healthz HTTP/1.1\r\nHost: x\r\n\r\n")) == 200);
}

// The availability test of the lobby: an attacker at 127.0.0.1 joins and leaves by mode and
// creates matches until refused; hosts at other addresses (127.0.0.2-4: the whole 127/8 is
// loopback) still join and create.
TEST_CASE("an address that creates matches and joins and leaves starves no other", "[net][ws][lobby][abuse]") {
    http_server s({"--modes", modes_file(), "--max-matches", "6"});
    auto join_by_mode = [&](const std::string& from) -> std::optional<protocol::welcome_info> {
        ws_client c(s.http_port, "", "/ws", 0, from);
        if (!c.open()) return std::nullopt;
        protocol::hello_msg hello{protocol::protocol_version, "x", "", true, false, "", "duel"};
        if (!c.send_binary(protocol::encode_hello(hello))) return std::nullopt;
        const auto frame = c.read_until(protocol::Payload::Welcome, 3000ms);
        if (!frame) return std::nullopt;
        auto welcome = protocol::decode_welcome(*message_of(*frame));
        if (!welcome) return std::nullopt;
        return welcome.value;  // and leaves, as the client closes
    };
    auto create_from = [&](const std::string& from) {
        return status_of(raw_http(s.http_port,
                                  "POST /matches HTTP/1.1\r\nHost: x\r\nContent-Length: 33\r\n\r\n"
                                  R"({"mode": "duel", "private": true})",
                                  3000ms, from));
    };
    // Joining and leaving reuses the match it made: one duel, however often.
    std::string first;
    for (int i = 0; i < 10; ++i) {
        const auto welcome = join_by_mode("127.0.0.1");
        REQUIRE(welcome);
        if (i == 0) first = welcome->match;
        CHECK(welcome->match == first);
    }
    // Then it creates until refused: it may hold 4 matches without a client.
    int created = 0;
    for (int i = 0; i < 8; ++i)
        if (create_from("127.0.0.1") == 201) ++created;
    CHECK(created == 3);                                   // its duel, empty now, is the fourth
    CHECK(get_json(s.http_port, "/matches").size() == 2);  // the default and the listed duel
    // Another host joins at once (the attacker's open duel has seats), and another creates.
    const auto honest = join_by_mode("127.0.0.2");
    REQUIRE(honest);
    CHECK(honest->mode == "duel");
    CHECK(create_from("127.0.0.3") == 201);  // the sixth of six
    CHECK(create_from("127.0.0.3") == 503);  // the process is full...
    std::this_thread::sleep_for(5500ms);
    CHECK(create_from("127.0.0.4") == 201);  // ...until a match empty for 5 s gives its slot up
}
