// The lobby on arena-server's HTTP port (server/host/lobby.*, docs/MATCHES.md) end to end:
// list, create (listed and private), join the created match by its id over the WebSocket,
// and the refusals: unknown mode, bad body, too large a body, a wrong method, no room.
#include <catch2/catch.hpp>
#include <fstream>
#include <nlohmann/json.hpp>

#include "protocol/decode.hpp"
#include "protocol/version.hpp"
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
    REQUIRE(modes.size() == 3);  // sandbox, asteroids, duel
    CHECK(modes[2]["name"] == "duel");
    CHECK(modes[2]["capacity"] == 2);
    CHECK(modes[2]["rules"] == "asteroids");
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
