#include "server/match/close_cause.hpp"

namespace arena::match {

std::string close_cause::key() const {
    switch (what) {
        case kind::rejected:
            return protocol::EnumNameRejectCode(code);
        case kind::client_bye:
            return "client said bye";
        case kind::connection_closed:
            return "connection closed";
        case kind::closed_mid_frame:
            return "connection closed mid-frame";
        case kind::socket_error:
            return "socket error";
        case kind::write_failed:
            return "write failed";
        case kind::taken_over:
            return "signed in from another connection";
        case kind::shutdown:
            return detail;
    }
    return "unknown";
}

std::string close_cause::text() const {
    switch (what) {
        case kind::rejected:
        case kind::client_bye:
        case kind::socket_error:
        case kind::write_failed:
            return key() + ": " + detail;
        case kind::connection_closed:
        case kind::closed_mid_frame:
        case kind::taken_over:
        case kind::shutdown:
            return key();
    }
    return key();
}

bool close_cause::connection_lost() const {
    return what == kind::connection_closed || what == kind::closed_mid_frame || what == kind::socket_error ||
           what == kind::write_failed;
}

}  // namespace arena::match
