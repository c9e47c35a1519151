#include "server/host/lobby.hpp"

#include <ctime>
#include <nlohmann/json.hpp>

#include "server/config/config_json.hpp"

namespace arena::host {

using nlohmann::json;

namespace {

constexpr std::string_view prefix = "/matches";

lobby_answer error(unsigned status, std::string text) {
    return {status, json{{"error", std::move(text)}}.dump() + "\n", "application/json"};
}

// RFC 3339, UTC, to the second: "2026-12-03T20:41:07Z"; "" when unknown.
std::string iso_time(int64_t unix_ms) {
    if (unix_ms <= 0) return "";
    const std::time_t seconds = static_cast<std::time_t>(unix_ms / 1000);
    std::tm utc{};
    gmtime_r(&seconds, &utc);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
    return text;
}

json describe(const hosted_match& m) {
    const match::match& g = *m.game;
    const uint32_t capacity = g.config().admission.max_players;
    const size_t players = g.live_player_count();
    const char* state = g.draining() || g.over() ? "ending" : players >= capacity ? "full" : "open";
    return {{"id", m.id},
            {"mode", m.mode},
            {"players", players},
            {"capacity", capacity},
            {"spectators", g.spectator_count()},
            {"tick", g.state().tick()},
            {"state", state},
            {"created", iso_time(m.created_unix_ms)},
            {"private", !m.listed}};
}

// The modes a client may ask for, with what a match of each holds.
lobby_answer list_modes(const match_registry& matches) {
    json list = json::array();
    for (const config::mode& m : matches.options().modes) {
        list.push_back({{"name", m.name},
                        {"capacity", m.max_players != 0 ? m.max_players : matches.options().base.admission.max_players},
                        {"preset", m.preset},
                        {"rules", m.world.rules},
                        {"duration", m.duration_s}});
    }
    return {200, list.dump() + "\n"};
}

lobby_answer create(match_registry& matches, const lobby_request& request, const match::token_check& check_token) {
    if (check_token) {
        constexpr std::string_view bearer = "Bearer ";
        const std::string_view auth = request.authorization;
        if (auth.substr(0, bearer.size()) != bearer)
            return error(401, "creating a match needs a join token: Authorization: Bearer TOKEN");
        if (auto name = check_token(auth.substr(bearer.size())); !name)
            return error(401, "token refused: " + name.error);
    }
    if (request.body.size() > max_lobby_body_bytes)
        return error(413, "the body is larger than " + std::to_string(max_lobby_body_bytes) + " bytes");
    const json body = json::parse(request.body, nullptr, false);
    if (body.is_discarded() || !body.is_object())
        return error(400, "the body must be a JSON object: {\"mode\": \"...\"}");
    for (const auto& [key, value] : body.items())
        if (key != "mode" && key != "private") return error(400, "unknown field '" + key.substr(0, 64) + "'");
    if (!body.contains("mode") || !body["mode"].is_string()) return error(400, "\"mode\" must be a string");
    if (body.contains("private") && !body["private"].is_boolean())
        return error(400, "\"private\" must be true or false");
    const bool is_private = body.value("private", false);
    auto made = matches.create(body["mode"].get<std::string>(), !is_private, request.address);
    if (auto* no = std::get_if<match::rejection>(&made)) {
        const unsigned status = no->code == protocol::RejectCode::mode_unknown ? 404 : 503;
        return error(status, no->detail);
    }
    return {201, describe(*std::get<hosted_match*>(made)).dump() + "\n"};
}

}  // namespace

bool is_lobby_path(std::string_view path) {
    return path == prefix || path == "/modes" ||
           (path.size() > prefix.size() + 1 && path.substr(0, prefix.size() + 1) == "/matches/");
}

lobby_answer answer_lobby(match_registry& matches, const lobby_request& request,
                          const match::token_check& check_token) {
    const bool read = request.method == "GET" || request.method == "HEAD";
    if (request.path == "/modes") return read ? list_modes(matches) : error(405, "GET or HEAD");
    if (request.path == prefix) {
        if (request.method == "POST") return create(matches, request, check_token);
        if (!read) return error(405, "GET, HEAD or POST");
        json list = json::array();
        for (const auto& [key, m] : matches.matches())
            if (m.listed) list.push_back(describe(m));
        return {200, list.dump() + "\n"};
    }
    if (!read) return error(405, "GET or HEAD");
    const std::string_view id = std::string_view(request.path).substr(prefix.size() + 1);
    const hosted_match* m = matches.find(id);
    if (!m) return error(404, "no match '" + std::string(id.substr(0, 64)) + "'");
    return {200, describe(*m).dump() + "\n"};
}

}  // namespace arena::host
