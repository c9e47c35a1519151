#include "server/rules/asteroids_params.hpp"

#include <cmath>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

namespace arena::rules {

namespace {

using nlohmann::json;

struct bad_param {
    std::string message;
};

// Reads the fields it is asked for, each within its range, and refuses the rest at the end.
class params_reader {
public:
    explicit params_reader(const json& j) : j_(j) {}

    void number(const char* name, world::real& out, double lo, double hi, bool lo_open = false) {
        const json* v = find(name);
        if (!v) return;
        const double d = v->is_number() ? v->get<double>() : NAN;
        if (!std::isfinite(d) || d < lo || (lo_open && d == lo) || d > hi)
            throw bad_param{field(name) + " must be a number in " + (lo_open ? "(" : "[") + text(lo) + ", " + text(hi) +
                            "]"};
        out = static_cast<world::real>(d);
    }
    void whole(const char* name, uint32_t& out, uint64_t lo, uint64_t hi) {
        const json* v = find(name);
        if (!v) return;
        if (!v->is_number_unsigned() || v->get<uint64_t>() < lo || v->get<uint64_t>() > hi)
            throw bad_param{field(name) + " must be a whole number in [" + std::to_string(lo) + ", " +
                            std::to_string(hi) + "]"};
        out = v->get<uint32_t>();
    }
    void finish() const {
        for (const auto& [key, value] : j_.items())
            if (!seen_.count(key)) throw bad_param{"unknown field " + field(key)};
    }

private:
    const json* find(const std::string& name) {
        seen_.insert(name);
        const auto it = j_.find(name);
        return it == j_.end() ? nullptr : &*it;
    }
    static std::string field(const std::string& name) { return "rules_params." + name; }
    static std::string text(double d) {
        std::string s = std::to_string(d);
        s.erase(s.find_last_not_of('0') + 1);
        if (s.back() == '.') s.pop_back();
        return s;
    }
    const json& j_;
    std::set<std::string> seen_;
};

}  // namespace

result<asteroids_params> parse_asteroids_params(std::string_view rules_params) {
    using out = result<asteroids_params>;
    asteroids_params p;
    if (rules_params.empty()) return out::success(p);
    try {
        const json j = json::parse(rules_params);
        if (!j.is_object()) return out::failure("rules_params must be an object");
        params_reader r(j);
        // Bounds that keep a match playable and its memory bounded: a bullet can neither stand
        // still nor be massless, a ship has at most 64 live bullets, counts stay in 32 bits.
        r.number("bullet_impulse", p.bullet_impulse, 0, 1e4, true);
        r.number("bullet_mass", p.bullet_mass, 0, 1e3, true);
        r.number("bullet_radius", p.bullet_radius, 0, 10, true);
        r.whole("fire_cooldown_ticks", p.fire_cooldown_ticks, 0, 36'000);
        r.whole("bullet_lifetime_ticks", p.bullet_lifetime_ticks, 1, 36'000);
        r.whole("max_bullets_per_ship", p.max_bullets_per_ship, 0, 64);
        r.whole("lives", p.lives, 0, 1'000);
        r.whole("respawn_ticks", p.respawn_ticks, 1, 36'000);
        r.whole("invulnerable_ticks", p.invulnerable_ticks, 0, 36'000);
        r.number("split_impulse", p.split_impulse, 0, 1e5);
        r.number("wave_rock_radius", p.wave_rock_radius, 0, 100, true);
        r.number("spawn_clearance", p.spawn_clearance, 0, 1e4);
        r.whole("score_large", p.score_large, 0, 1'000'000);
        r.whole("score_medium", p.score_medium, 0, 1'000'000);
        r.whole("score_small", p.score_small, 0, 1'000'000);
        r.whole("score_ship", p.score_ship, 0, 1'000'000);
        r.finish();
    } catch (const bad_param& e) {
        return out::failure(e.message);
    } catch (const json::exception& e) {
        return out::failure(std::string("rules_params: invalid JSON: ") + e.what());
    }
    return out::success(p);
}

}  // namespace arena::rules
