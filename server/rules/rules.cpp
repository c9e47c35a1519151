#include "server/rules/rules.hpp"

#include <stdexcept>

#include "server/rules/asteroids_rules.hpp"

namespace arena::rules {

namespace {

std::string sandbox_params_problem(const world::world_config& config) {
    if (config.rules_params.empty() || config.rules_params == "{}") return "";
    return "rules_params: the sandbox rules take no parameters";
}

}  // namespace

std::unique_ptr<rules> make_rules(world::world& w) {
    switch (w.config().rules) {
        case world::game_rules::asteroids: {
            auto params = parse_asteroids_params(w.config().rules_params);
            if (!params) throw std::invalid_argument(params.error);
            return std::make_unique<asteroids_rules>(w, params.value);
        }
        case world::game_rules::sandbox:
            break;
    }
    if (const std::string problem = sandbox_params_problem(w.config()); !problem.empty())
        throw std::invalid_argument(problem);
    return std::make_unique<rules>();
}

std::string rules_params_problem(const world::world_config& config) {
    switch (config.rules) {
        case world::game_rules::asteroids:
            return parse_asteroids_params(config.rules_params).error;
        case world::game_rules::sandbox:
            break;
    }
    return sandbox_params_problem(config);
}

uint64_t state_hash(const world::world& w, const rules& r) {
    if (!r.has_state()) return w.hash();
    world::fnv1a h;
    h.add_u64(w.hash());
    r.hash(h);
    return h.value();
}

}  // namespace arena::rules
