#pragma once
// Why a connection ended, as a type: the log line's text and the counters' key both come from
// it, so nobody searches a reason string for a word or splits it at a colon.
#include <cstdint>
#include <string>

#include "protocol/arena_generated.h"

namespace arena::match {

// A refusal: the code the client reads in its Reject, and a one-line detail for it and the log.
struct rejection {
    protocol::RejectCode code = protocol::RejectCode::bad_request;
    std::string detail;
};

struct close_cause {
    enum class kind : std::uint8_t {
        rejected,           // the server sent Reject(code, detail)
        client_bye,         // the client sent Bye(detail)
        connection_closed,  // end of stream between frames
        closed_mid_frame,   // end of stream inside a frame
        socket_error,       // the transport failed to read (detail: the error)
        write_failed,       // the transport failed to write (detail: the error)
        taken_over,         // a new connection with the same identity took the player
        shutdown,           // the server shuts down (detail: why, e.g. "server terminated (SIGTERM)")
    };
    kind what = kind::connection_closed;
    protocol::RejectCode code = protocol::RejectCode::bad_request;  // with kind::rejected
    std::string detail;

    static close_cause of(const rejection& r) { return {kind::rejected, r.code, r.detail}; }

    // The whole reason, as log lines show it: "bad_input: thrust is not a finite number",
    // "client said bye: done", "connection closed".
    [[nodiscard]] std::string text() const;
    // The counter it adds to (`closes` in --stats-json): the code's name, "client said bye",
    // "connection closed", "socket error", ..., or the shutdown's reason.
    [[nodiscard]] std::string key() const;
    // True when the client did not choose to go: its body waits for a reconnection.
    [[nodiscard]] bool connection_lost() const;
};

}  // namespace arena::match
