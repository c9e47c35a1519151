#pragma once
// The ops flags of arena-server, so that its main adds them in one line and tests can parse
// them: --metrics-port, --metrics-bind, --serve-recording, --agones, --agones-port,
// --agones-shutdown-timeout.
#include <CLI/CLI.hpp>
#include <string>

#include "server/ops/ops_service.hpp"

namespace arena::ops {

void add_ops_flags(CLI::App& app, ops_options& options);

// After parsing: AGONES_SDK_HTTP_PORT (the value Agones sets in the game server's container,
// or nullptr) turns Agones on and gives the sidecar's port unless --agones-port was given.
// Returns an error message for a malformed value, "" otherwise.
std::string apply_agones_environment(ops_options& options, const char* sdk_http_port);

}  // namespace arena::ops
