#pragma once
// How a game reads its "rules_params" (a world config's object, as canonical JSON text): every
// field optional, each within its range, anything else refused with the field's name. Every
// game reads its parameters with it, so every game's errors read the same:
//
//   result<my_params> parse_my_params(std::string_view text) {
//       my_params p;
//       return read_params(text, p, [](params_reader& r, my_params& p) {
//           r.number("kick_impulse", p.kick_impulse, 0, 1e3, true);
//           r.whole("players_per_team", p.players_per_team, 1, 32);
//       });
//   }
#include <cstdint>
#include <functional>
#include <nlohmann/json_fwd.hpp>
#include <set>
#include <string>
#include <string_view>

#include "server/world/result.hpp"
#include "server/world/types.hpp"

namespace arena::rules {

class params_reader {
public:
    explicit params_reader(const nlohmann::json& object) : object_(object) {}

    // A number in [lo, hi] ((lo, hi] when lo_open); left as it is when absent.
    void number(const char* name, world::real& out, double lo, double hi, bool lo_open = false);
    // A whole number in [lo, hi]; left as it is when absent.
    void whole(const char* name, uint32_t& out, uint64_t lo, uint64_t hi);
    // Refuses any field none of the calls above asked for.
    void finish() const;

private:
    const nlohmann::json* find(const std::string& name);

    const nlohmann::json& object_;
    std::set<std::string> seen_;
};

// Why `rules_params` ("" or "{}": none) cannot be read by `fields` (called once with a reader
// over the object; it reads each field into wherever it likes): "rules_params.FIELD must be a
// number in [0, 10]", "unknown field rules_params.x", or "" when it can.
std::string read_params_problem(std::string_view rules_params, const std::function<void(params_reader&)>& fields);

// The parameters `rules_params` give: `defaults` with the fields `fields(reader, params)` reads,
// or read_params_problem's line.
template <class Params, class Fields>
result<Params> read_params(std::string_view rules_params, Params defaults, Fields fields) {
    std::string problem = read_params_problem(rules_params, [&](params_reader& r) { fields(r, defaults); });
    if (!problem.empty()) return result<Params>::failure(std::move(problem));
    return result<Params>::success(defaults);
}

}  // namespace arena::rules
