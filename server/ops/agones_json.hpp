#pragma once
// The JSON of the Agones SDK sidecar's Counters, Lists and GameServer watch, as its REST API
// (grpc-gateway) writes it: int64 fields are JSON strings ("3"), empty fields may be left out,
// and each event of GET /watch/gameserver is one line {"result": {GameServer}}.
// Header-only (inline): it is read by density_sync.hpp and the tests alone.
#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace arena::ops {

// What the process reads of a GameServer on the watch.
struct gameserver_view {
    std::string last_allocated{};          // annotation agones.dev/last-allocated: changes with each allocation
    std::string mode{};                    // annotation arena.dev/mode: what the allocated match plays
    std::string match{};                   // annotation arena.dev/match: its id ("": a new random one)
    std::optional<int64_t> rooms_count{};  // status.counters.rooms.count; nullopt: not declared
    bool players_declared = false;         // status.lists.players exists
};

namespace agones_json {

// An int64 as grpc-gateway writes it (a string), or as a plain number; absent: 0 (proto3 leaves
// zeros out). nullopt: something else.
inline std::optional<int64_t> int64_of(const nlohmann::json& j) {
    if (j.is_null()) return 0;
    if (j.is_number_integer()) return j.get<int64_t>();
    if (!j.is_string()) return std::nullopt;
    const std::string& s = j.get_ref<const std::string&>();
    try {
        size_t used = 0;
        const long long v = std::stoll(s, &used);
        if (used != s.size()) return std::nullopt;
        return static_cast<int64_t>(v);
    } catch (const std::exception&) {
        return std::nullopt;
    }
}

inline nlohmann::json parse(std::string_view text) {
    return nlohmann::json::parse(text.begin(), text.end(), nullptr, false);  // discarded on error
}

inline const nlohmann::json* member(const nlohmann::json& j, const char* key) {
    if (!j.is_object()) return nullptr;
    const auto it = j.find(key);
    return it == j.end() ? nullptr : &*it;
}

inline std::string string_member(const nlohmann::json* j, const char* key) {
    const nlohmann::json* v = j ? member(*j, key) : nullptr;
    return v && v->is_string() ? v->get<std::string>() : std::string();
}

// PATCH /v1beta1/counters/NAME's body.
inline std::string count_diff_body(int64_t diff) {
    return nlohmann::json{{"countDiff", std::to_string(diff)}}.dump();
}

// POST /v1beta1/lists/NAME:addValue and :removeValue's body.
inline std::string list_value_body(const std::string& value) {
    return nlohmann::json{{"value", value}}.dump();
}

// GET /v1beta1/counters/NAME's answer: its count.
inline std::optional<int64_t> counter_count(std::string_view body) {
    const nlohmann::json j = parse(body);
    if (!j.is_object()) return std::nullopt;
    const nlohmann::json* count = member(j, "count");
    return count ? int64_of(*count) : 0;
}

// GET /v1beta1/lists/NAME's answer: its values.
inline std::optional<std::vector<std::string>> list_values(std::string_view body) {
    const nlohmann::json j = parse(body);
    if (!j.is_object()) return std::nullopt;
    std::vector<std::string> values;
    if (const nlohmann::json* v = member(j, "values")) {
        if (!v->is_array()) return std::nullopt;
        for (const auto& e : *v)
            if (e.is_string()) values.push_back(e.get<std::string>());
    }
    return values;
}

// One line of GET /watch/gameserver; nullopt for a line that is no GameServer (an error event).
// The SDK's GameServer names its metadata object_meta; metadata is read too.
inline std::optional<gameserver_view> watch_event(std::string_view line) {
    const nlohmann::json j = parse(line);
    const nlohmann::json* gs = member(j, "result");
    if (!gs || !gs->is_object()) return std::nullopt;
    gameserver_view view;
    const nlohmann::json* meta = member(*gs, "object_meta");
    if (!meta) meta = member(*gs, "metadata");
    const nlohmann::json* annotations = meta ? member(*meta, "annotations") : nullptr;
    view.last_allocated = string_member(annotations, "agones.dev/last-allocated");
    view.mode = string_member(annotations, "arena.dev/mode");
    view.match = string_member(annotations, "arena.dev/match");
    const nlohmann::json* status = member(*gs, "status");
    const nlohmann::json* counters = status ? member(*status, "counters") : nullptr;
    if (const nlohmann::json* rooms = counters ? member(*counters, "rooms") : nullptr) {
        const nlohmann::json* count = member(*rooms, "count");
        view.rooms_count = count ? int64_of(*count) : 0;
    }
    const nlohmann::json* lists = status ? member(*status, "lists") : nullptr;
    view.players_declared = lists && member(*lists, "players");
    return view;
}

// Whether an error answer says the GameServer has no such Counter or List. Agones' sidecar
// answers it with "counter not found: NAME" / "list not found: NAME" (HTTP 500 from the
// gateway in the versions we know, 404 where it maps the code).
inline bool says_unknown_key(std::string_view body) {
    return body.find("counter not found") != std::string_view::npos ||
           body.find("list not found") != std::string_view::npos;
}

}  // namespace agones_json
}  // namespace arena::ops
