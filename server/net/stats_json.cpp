#include "server/net/stats_json.hpp"

namespace arena::net {

nlohmann::json* stats_json_sink::field(const match::figure& f) {
    if (f.stats.empty()) return nullptr;
    return &out_[nlohmann::json::json_pointer("/" + std::string(f.stats))];
}

void stats_json_sink::counters_by(const match::figure& f, std::string_view,
                                  const std::map<std::string, uint64_t>& values) {
    nlohmann::json* at = field(f);
    if (!at) return;
    *at = nlohmann::json::object();  // the kinds that happened: a zero is no news in a run's summary
    for (const auto& [key, count] : values)
        if (count != 0) (*at)[key] = count;
}

}  // namespace arena::net
