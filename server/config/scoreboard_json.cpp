#include "server/config/scoreboard_json.hpp"

#include <nlohmann/json.hpp>

namespace arena::config {

std::string scoreboard_json(std::span<const rules::score_line> lines, std::span<const std::string> names,
                            const protocol::game_manifest* game) {
    nlohmann::json board = nlohmann::json::array();
    for (size_t k = 0; k < lines.size(); ++k) {
        const rules::score_line& s = lines[k];
        board.push_back({{"player", s.player},
                         {"name", k < names.size() ? names[k] : std::string()},
                         {"score", s.score},
                         {"kills", s.kills},
                         {"deaths", s.deaths},
                         {"shots", s.shots},
                         {"hits", s.hits}});
        if (s.team != 0) board.back()["team"] = s.team;  // a team game's only
        if (game == nullptr) continue;
        for (size_t f = 0; f < game->player_fields.size() && f < s.values.size(); ++f)
            if (!board.back().contains(game->player_fields[f].name))
                board.back()[game->player_fields[f].name] = s.values[f];
    }
    return board.dump();
}

}  // namespace arena::config
