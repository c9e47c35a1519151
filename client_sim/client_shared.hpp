#pragma once
// What the client cores of one process share: the figures they add to, one FlatBufferBuilder
// for their Inputs and Pings (one thread, so sharing is safe), and the Welcome's world_config
// parsed once for all of them. arena-bots' fleet is one (it overrides the hooks); a test over
// the simulated network uses one as it is.
#include <cstdint>
#include <optional>
#include <string>

#include "client_sim/metrics.hpp"
#include "client_sim/session.hpp"
#include "protocol/messages.hpp"
#include "server/world/config.hpp"

namespace arena::bots {

class client_shared : public config_source {
public:
    client_shared() = default;
    client_shared(const client_shared&) = delete;
    client_shared& operator=(const client_shared&) = delete;
    virtual ~client_shared() = default;

    fleet_metrics& metrics() { return metrics_; }
    const fleet_metrics& metrics() const { return metrics_; }
    flatbuffers::FlatBufferBuilder& encoder() { return encoder_; }

    // The Welcome's world_config parsed once per distinct text (1000 bots share one), or why
    // it does not parse.
    result<const world::world_config*> config_for(const protocol::welcome_info& welcome) override;

    // True once the run is ending: a session that ends now did not end early.
    [[nodiscard]] bool stopping() const { return stopping_; }
    void set_stopping() { stopping_ = true; }

    // A core got its Welcome.
    virtual void on_joined(const protocol::welcome_info& welcome);
    // A core's session ended; was_playing: it had joined.
    virtual void on_ended(bool was_playing);

    [[nodiscard]] std::uint32_t playing() const { return playing_; }
    [[nodiscard]] std::uint32_t ended() const { return ended_; }

private:
    fleet_metrics metrics_;
    flatbuffers::FlatBufferBuilder encoder_{256};
    bool stopping_ = false;
    std::uint32_t playing_ = 0;
    std::uint32_t ended_ = 0;
    std::string config_text_;  // the world_config that config_ was parsed from
    std::optional<world::world_config> config_;
};

}  // namespace arena::bots
