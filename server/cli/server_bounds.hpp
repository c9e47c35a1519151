#pragma once
// The bounds of arena-server's numeric flags that a conversion could overflow: seconds go to
// int64 nanoseconds (overflow past 292 years) and the reconnect grace to uint32 ticks
// (wrapped at 71 582 789 s at 60 Hz). Every bound is far beyond any sensible setting and far
// below an overflow at the highest --tick-rate (1000); a value outside is refused (exit 2).
#include "server/cli/bounds.hpp"

namespace arena::cli {

inline constexpr number_bound handshake_timeout_bound{0, 3600, true, "s"};
inline constexpr number_bound stall_timeout_bound{0, 3600, true, "s"};
inline constexpr number_bound idle_timeout_bound{0, 3600, false, "s"};  // 0: never
inline constexpr number_bound stats_interval_bound{0, 86400, true, "s"};
// 30 days: 2.6e9 ticks at 1000 Hz still fit the world's 32-bit tick counter. 0: until a signal.
inline constexpr number_bound duration_bound{0, 30 * 86400, false, "s"};
inline constexpr number_bound reconnect_grace_bound{0, 3600, false, "s"};
inline constexpr number_bound drain_grace_bound{0, 60, false, "s"};
// Snapshots are quantised to ±8 388 km (protocol/delta/quantize.hpp): a larger radius is "all".
inline constexpr number_bound view_radius_bound{0, 1e7, false, "m"};
inline constexpr number_bound agones_shutdown_timeout_bound{0, 3600, true, "s"};

// Adds the bounds above to arena-server's flags; call after declaring them.
inline void bound_server_flags(CLI::App& app) {
    bound_option(app, "--handshake-timeout", handshake_timeout_bound);
    bound_option(app, "--stall-timeout", stall_timeout_bound);
    bound_option(app, "--idle-timeout", idle_timeout_bound);
    bound_option(app, "--stats-interval", stats_interval_bound);
    bound_option(app, "--duration", duration_bound);
    bound_option(app, "--reconnect-grace", reconnect_grace_bound);
    bound_option(app, "--drain-grace", drain_grace_bound);
    bound_option(app, "--view-radius", view_radius_bound);
    bound_option(app, "--agones-shutdown-timeout", agones_shutdown_timeout_bound);  // server/ops/ops_flags.cpp
}

}  // namespace arena::cli
