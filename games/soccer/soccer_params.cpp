#include "games/soccer/soccer_params.hpp"

#include "server/rules/params_reader.hpp"

namespace arena::rules {

result<soccer_params> parse_soccer_params(std::string_view rules_params) {
    return read_params(rules_params, soccer_params{}, [](params_reader& r, soccer_params& p) {
        // A match of a second to a day; a kick that moves the ball without launching it past any
        // pitch in one step; friction that may be none but never accelerates.
        r.whole("match_seconds", p.match_seconds, 1, 86'400);
        r.whole("periods", p.periods, 1, 16);
        r.number("kick_impulse", p.kick_impulse, 0, 1e3, true);
        r.number("kick_reach", p.kick_reach, 0, 10);
        r.whole("kick_cooldown_ticks", p.kick_cooldown_ticks, 0, 36'000);
        r.number("ball_friction", p.ball_friction, 0, 10);
        r.number("gravity", p.gravity, 0, 100);
        r.whole("kickoff_ticks", p.kickoff_ticks, 0, 36'000);
    });
}

}  // namespace arena::rules
