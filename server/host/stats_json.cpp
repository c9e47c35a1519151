#include "server/host/stats_json.hpp"

namespace arena::host {

nlohmann::json* stats_json_sink::field(const match::figure& f) {
    if (f.stats.empty()) return nullptr;
    // Appended, not "/" + string: g++ 12 warns (-Wrestrict) on the inlined insert, wrongly.
    std::string pointer = "/";
    pointer.append(f.stats);
    return &out_[nlohmann::json::json_pointer(pointer)];
}

void stats_json_sink::counters_by(const match::figure& f, std::string_view,
                                  const std::map<std::string, uint64_t>& values) {
    nlohmann::json* at = field(f);
    if (!at) return;
    *at = nlohmann::json::object();  // the kinds that happened: a zero is no news in a run's summary
    for (const auto& [key, count] : values)
        if (count != 0) (*at)[key] = count;
}

}  // namespace arena::host
