#pragma once
// The --stats-json writer's side of figures.hpp: each figure with a stats name becomes a field
// ("snapshots/delta_frames" nests), so that a figure named once in a report() appears here.
#include <nlohmann/json.hpp>

#include "server/match/figures.hpp"

namespace arena::host {

class stats_json_sink : public match::figure_sink {
public:
    explicit stats_json_sink(nlohmann::json& out) : out_(out) {}
    void counter(const match::figure& f, uint64_t value) override { set(f, value); }
    void gauge(const match::figure& f, uint64_t value) override { set(f, value); }
    void gauge(const match::figure& f, double value) override { set(f, value); }
    void counters_by(const match::figure& f, std::string_view label,
                     const std::map<std::string, uint64_t>& values) override;

private:
    nlohmann::json* field(const match::figure& f);
    template <class T>
    void set(const match::figure& f, T value) {
        if (nlohmann::json* at = field(f)) *at = value;
    }
    nlohmann::json& out_;
};

}  // namespace arena::host
