#include "server/rules/rules.hpp"

#include <stdexcept>

#include "server/rules/asteroids_rules.hpp"

namespace arena::rules {

std::unique_ptr<rules> make_rules(world::world& w) {
    if (const std::string problem = rules_params_problem(w.config()); !problem.empty())
        throw std::invalid_argument(problem);
    switch (w.config().rules) {
        case world::game_rules::asteroids:
            return std::make_unique<asteroids_rules>(w, parse_asteroids_params(w.config().rules_params).value);
        case world::game_rules::sandbox:
            break;
    }
    return std::make_unique<rules>();
}

std::string rules_params_problem(const world::world_config& config) {
    switch (config.rules) {
        case world::game_rules::asteroids:
            return parse_asteroids_params(config.rules_params).error;
        case world::game_rules::sandbox:
            break;
    }
    if (config.rules_params.empty() || config.rules_params == "{}") return "";
    return "rules_params: the sandbox rules take no parameters";
}

uint64_t state_hash(const world::world& w, const rules& r) {
    if (!r.has_state()) return w.hash();
    world::fnv1a h;
    h.add_u64(w.hash());
    r.hash(h);
    return h.value();
}

}  // namespace arena::rules
