#include "server/match/connection.hpp"

#include "server/match/match.hpp"

namespace arena::match {

connection::~connection() {
    // The match still holds it: it marks its record, and clears no pointer in a connection
    // that is gone when it ends.
    if (record) record->connection_gone = true;
}

}  // namespace arena::match
